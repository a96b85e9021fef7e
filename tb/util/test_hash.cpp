// SPDX-License-Identifier: Apache-2.0
// util/hash.h: FNV-1a 64 against the published test vectors (Fowler/Noll/Vo), and the
// cache key's value pinned from an independent computation (Python, the same byte loop),
// so a change of seed or separator, which would rename every cache entry, fails here.
#include <gtest/gtest.h>

#include "util/hash.h"

namespace rastsim {
namespace {

TEST(Hash, Fnv1a64PublishedVectors) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
  // Continued from a value: the same as hashing the concatenation.
  EXPECT_EQ(fnv1a64("bar", fnv1a64("foo")), fnv1a64("foobar"));
  EXPECT_EQ(hex64(0xcbf29ce484222325ull), "cbf29ce484222325");
  EXPECT_EQ(hex64(0x1ull), "0000000000000001");
}

TEST(Hash, CacheKeySeparatesItsParts) {
  EXPECT_EQ(Fnv64{}.hex(), "14650fb0739d0383");
  Fnv64 a, b;
  for (const char* s : {"rastsim-rtl-1", "ab", "c"}) a.add(s);
  for (const char* s : {"rastsim-rtl-1", "a", "bc"}) b.add(s);
  EXPECT_EQ(a.hex(), "9c7c7ae20e931958");
  EXPECT_EQ(b.hex(), "61112a59d0e682ce");
}

}  // namespace
}  // namespace rastsim
