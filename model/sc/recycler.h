// SPDX-License-Identifier: Apache-2.0
// Recycler<T>: the objects a stage sends downstream behind a shared_ptr (a set-up
// triangle, a tile's pixel batch, its fragments), reused once every holder has let go,
// so a transaction costs no heap allocation in the steady state (the object, its
// shared_ptr control block and, for vectors, their storage, which keeps its capacity).
//
// An object is free when the pool's own pointer is its only owner (use_count 1: the
// SystemC stages run on one OS thread, so no holder can appear meanwhile). At most the
// objects in flight are ever alive, a few more than the FIFO depths between the stage
// and the last reader, so the pool stays small; it is scanned round-robin from where
// the last free object was found, which is usually the oldest in flight.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace rastsim::sc {

template <class T>
class Recycler {
 public:
  // A free object (as its last user left it: the caller resets what it reuses), or a
  // new default-constructed one when every pooled object is still held.
  std::shared_ptr<T> take() {
    for (size_t i = 0; i < pool_.size(); ++i) {
      next_ = next_ + 1 < pool_.size() ? next_ + 1 : 0;
      if (pool_[next_].use_count() == 1) return pool_[next_];
    }
    next_ = pool_.size();
    return pool_.emplace_back(std::make_shared<T>());
  }

 private:
  std::vector<std::shared_ptr<T>> pool_;
  size_t next_ = 0;  // where the last object was taken
};

}  // namespace rastsim::sc
