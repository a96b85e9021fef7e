// SPDX-License-Identifier: Apache-2.0
// LocalPtr<T>: the shared pointer of the objects the stages pass each other (a command,
// a set-up triangle, a tile's pixel batch, its fragments), as std::shared_ptr but with
// a plain count instead of an atomic one.
//
// Why: every SystemC stage runs on the one OS thread of the simulation, so no count is
// ever touched by two threads, and std::shared_ptr's atomic increments and decrements
// (a locked instruction each, since the process has the scene reader's thread too) were
// about a tenth of `simulate`'s stage code on small triangles, a few per transaction.
// Never hand a LocalPtr to another thread.
//
// The count lives in a LocalOwner: a heap block (make_local: freed with its last
// pointer, as a streamed scene's command batch) or a pooled object (sc/recycler.h: free
// again for reuse when its count is 0, never freed by the pointers). A pointer with no
// owner borrows its object (the caller keeps it alive), as an aliasing shared_ptr with an
// empty owner does. The aliasing constructor points into an owner's object (a command
// within its batch).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

namespace rastsim::sc {

class LocalOwner {
 public:
  LocalOwner() = default;
  LocalOwner(const LocalOwner&) = delete;
  LocalOwner& operator=(const LocalOwner&) = delete;
  uint32_t use_count() const { return refs_; }

 protected:
  // pooled: kept by its pool when the last pointer lets go; else deleted then.
  explicit LocalOwner(bool pooled) : pooled_(pooled) {}
  virtual ~LocalOwner() = default;

 private:
  template <class T>
  friend class LocalPtr;
  void acquire() { ++refs_; }
  void release() {
    if (--refs_ == 0 && !pooled_) delete this;
  }
  uint32_t refs_ = 0;  // LocalPtrs naming this owner
  bool pooled_ = false;
};

template <class T>
class LocalPtr {
 public:
  LocalPtr() = default;
  LocalPtr(std::nullptr_t) {}  // NOLINT: as shared_ptr, null converts implicitly
  // Shares `owner` (may be null: borrowed) and points at p.
  LocalPtr(LocalOwner* owner, T* p) : p_(p), owner_(owner) { acquire(); }
  // Aliasing: shares `other`'s owner and points at p (an object it keeps alive).
  template <class U>
  LocalPtr(const LocalPtr<U>& other, T* p) : LocalPtr(other.owner_, p) {}
  LocalPtr(const LocalPtr& o) : LocalPtr(o.owner_, o.p_) {}
  LocalPtr(LocalPtr&& o) noexcept : p_(std::exchange(o.p_, nullptr)), owner_(std::exchange(o.owner_, nullptr)) {}
  // LocalPtr<const T> from LocalPtr<T>.
  template <class U>
  LocalPtr(const LocalPtr<U>& o) : LocalPtr(o.owner_, o.p_) {}  // NOLINT: as shared_ptr
  template <class U>
  LocalPtr(LocalPtr<U>&& o) noexcept  // NOLINT: as shared_ptr
      : p_(std::exchange(o.p_, nullptr)), owner_(std::exchange(o.owner_, nullptr)) {}
  LocalPtr& operator=(LocalPtr o) noexcept {
    std::swap(p_, o.p_);
    std::swap(owner_, o.owner_);
    return *this;
  }
  ~LocalPtr() {
    if (owner_) owner_->release();
  }

  T* get() const { return p_; }
  T& operator*() const { return *p_; }
  T* operator->() const { return p_; }
  explicit operator bool() const { return p_ != nullptr; }
  // Equal when they point at the same object (as shared_ptr: owners not compared).
  bool operator==(const LocalPtr& o) const { return p_ == o.p_; }

 private:
  template <class U>
  friend class LocalPtr;
  void acquire() {
    if (owner_) owner_->acquire();
  }
  T* p_ = nullptr;
  LocalOwner* owner_ = nullptr;
};

// A heap block that holds one T and frees itself with its last LocalPtr.
template <class T>
class LocalBlock final : public LocalOwner {
 public:
  template <class... Args>
  explicit LocalBlock(Args&&... args) : LocalOwner(false), value(std::forward<Args>(args)...) {}
  T value;
};

template <class T, class... Args>
LocalPtr<T> make_local(Args&&... args) {
  auto* b = new LocalBlock<T>(std::forward<Args>(args)...);
  return LocalPtr<T>(b, &b->value);
}

// An object of a pool (sc/recycler.h): free when no LocalPtr names it.
template <class T>
class Pooled final : public LocalOwner {
 public:
  Pooled() : LocalOwner(true) {}
  T value{};
};

}  // namespace rastsim::sc
