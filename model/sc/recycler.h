// SPDX-License-Identifier: Apache-2.0
// Recycler<T>: the objects a stage sends downstream behind a LocalPtr (a set-up
// triangle, a tile's pixel batch, its fragments), reused once every holder has let go,
// so a transaction costs no heap allocation in the steady state (the object and, for
// vectors, their storage, which keeps its capacity).
//
// An object is free when no LocalPtr names it (count 0: sc/local_ptr.h; the SystemC
// stages run on one OS thread, so no holder can appear meanwhile). At most the objects
// in flight are ever alive, a few more than the FIFO depths between the stage and the
// last reader, so the pool stays small; it is scanned round-robin from where the last
// free object was found, which is usually the oldest in flight.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "sc/local_ptr.h"

namespace rastsim::sc {

template <class T>
class Recycler {
 public:
  // A free object (as its last user left it: the caller resets what it reuses), or a
  // new default-constructed one when every pooled object is still held.
  LocalPtr<T> take() {
    for (size_t i = 0; i < pool_.size(); ++i) {
      next_ = next_ + 1 < pool_.size() ? next_ + 1 : 0;
      Pooled<T>& o = *pool_[next_];
      if (o.use_count() == 0) return LocalPtr<T>(&o, &o.value);
    }
    next_ = pool_.size();
    Pooled<T>& o = *pool_.emplace_back(std::make_unique<Pooled<T>>());
    return LocalPtr<T>(&o, &o.value);
  }

 private:
  std::vector<std::unique_ptr<Pooled<T>>> pool_;
  size_t next_ = 0;  // where the last object was taken
};

}  // namespace rastsim::sc
