// SPDX-License-Identifier: Apache-2.0
// sc::LocalPtr and sc::Recycler (sc/local_ptr.h, sc/recycler.h): the counts the stages'
// payloads rely on. A heap block lives exactly as long as its last pointer (aliasing
// pointers into it included), a borrowed pointer owns nothing, and a pooled object is
// handed out again only once no pointer names it.
#include <gtest/gtest.h>

#include <vector>

#include "sc/recycler.h"

namespace rastsim::sctest {
namespace {

// Counts its destructions into *dead.
struct Tracked {
  int* dead = nullptr;
  int value = 0;
  explicit Tracked(int* d, int v = 0) : dead(d), value(v) {}
  ~Tracked() { ++*dead; }
};

TEST(ScLocalPtr, BlockFreedWithItsLastPointerAliasesIncluded) {
  int dead = 0;
  {
    sc::LocalPtr<const std::vector<Tracked>> owner;
    sc::LocalPtr<const Tracked> second;
    {
      std::vector<Tracked> v;
      v.reserve(3);
      for (int k = 0; k < 3; ++k) v.emplace_back(&dead, k);
      owner = sc::make_local<std::vector<Tracked>>(std::move(v));
      second = sc::LocalPtr<const Tracked>(owner, &(*owner)[1]);  // into the block
    }
    sc::LocalPtr<const Tracked> copy = second;
    owner = nullptr;
    EXPECT_EQ(dead, 0);  // the aliases keep the whole block
    EXPECT_EQ(copy->value, 1);
    second = nullptr;
    EXPECT_EQ(dead, 0);
    sc::LocalPtr<const Tracked> moved = std::move(copy);
    EXPECT_FALSE(copy);  // NOLINT(bugprone-use-after-move): moved-from is null, as shared_ptr
    EXPECT_EQ(moved->value, 1);
  }
  EXPECT_EQ(dead, 3);  // freed once, with the last pointer
}

TEST(ScLocalPtr, BorrowedPointerOwnsNothing) {
  int dead = 0;
  {
    Tracked t(&dead, 7);
    {
      const sc::LocalPtr<const Tracked> a(nullptr, &t);
      const sc::LocalPtr<const Tracked> b = a;
      EXPECT_EQ(b->value, 7);
      EXPECT_TRUE(a == b);
    }
    EXPECT_EQ(dead, 0);
  }
  EXPECT_EQ(dead, 1);  // by its own scope only
}

TEST(ScRecycler, ObjectReusedOnlyWhenNoPointerNamesIt) {
  sc::Recycler<std::vector<int>> pool;
  sc::LocalPtr<std::vector<int>> a = pool.take();
  a->assign(100, 1);
  const std::vector<int>* first = a.get();
  sc::LocalPtr<const std::vector<int>> reader = a;  // a downstream holder
  a = nullptr;
  sc::LocalPtr<std::vector<int>> b = pool.take();
  EXPECT_NE(b.get(), first);  // still held by `reader`
  reader = nullptr;
  b = nullptr;
  sc::LocalPtr<std::vector<int>> c = pool.take();
  sc::LocalPtr<std::vector<int>> d = pool.take();
  // Both pooled objects are free again and handed out, none new: the first kept its
  // contents (and capacity) as its last user left it.
  EXPECT_TRUE(c.get() == first || d.get() == first);
  EXPECT_EQ((c.get() == first ? c : d)->size(), 100u);
  EXPECT_NE(c.get(), d.get());
}

}  // namespace
}  // namespace rastsim::sctest
