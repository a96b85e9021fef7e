// SPDX-License-Identifier: Apache-2.0
// A set-associative cache's tag store, functional and untimed: which lines it holds,
// which are dirty, which line a miss evicts. Write-back, write-allocate, true LRU:
// a miss takes an invalid way of its set if there is one, else the way used least
// recently (every access, hit or miss, makes its line the most recently used). The
// caller counts bytes (surface_client.h); this model only decides hits and victims.
//
// Lines are numbered: line = byte offset / line_bytes; the set is line mod sets (sets =
// bytes / (ways x line_bytes), a power of two), as a hardware index of the low line bits.
#pragma once

#include <cstdint>
#include <vector>

#include "ref/memory/memory_params.h"

namespace rastsim {

class SetAssocCache {
 public:
  struct Victim {
    bool valid = false;  // a line was evicted
    bool dirty = false;  // ... and must be written back
    uint64_t line = 0;
  };

  // p.bytes > 0, a multiple of ways x line_bytes with a power-of-two quotient.
  explicit SetAssocCache(const CacheParams& p);

  // One access to `line`: true on a hit. On a miss the line is allocated (write-allocate)
  // and the line it replaced, if any, is returned in `victim`. A write marks it dirty.
  // Inline fast path: the line the previous access used is the most recently used of its
  // set already, so a repeat hit (consecutive samples of a line) leaves the LRU order as
  // it is and only marks the line dirty (LRU compares last_use values, never reads uses_).
  bool access(uint64_t line, bool write, Victim& victim) {
    if (mru_ != kNoWay && ways_[mru_].line == line) {
      ways_[mru_].dirty = ways_[mru_].dirty || write;
      return true;
    }
    return access_set(line, write, victim);
  }
  bool holds(uint64_t line) const;

  // f(line) for every dirty line, set by set, ways in order; then every line is clean.
  template <class F>
  void write_back_all(F&& f) {
    for (Way& w : ways_)
      if (w.valid && w.dirty) {
        f(w.line);
        w.dirty = false;
      }
  }
  // Every line invalid, dirty data dropped (a clear overwrites the whole surface).
  void invalidate_all();

  int line_bytes() const { return line_bytes_; }
  int ways() const { return n_ways_; }
  uint64_t sets() const { return set_mask_ + 1; }

 private:
  struct Way {
    uint64_t line = 0;
    uint64_t last_use = 0;  // access number of its last use: the smallest in a set is the LRU
    bool valid = false, dirty = false;
  };
  bool access_set(uint64_t line, bool write, Victim& victim);  // access() past the fast path

  std::vector<Way> ways_;  // set-major: set k's ways at [k ways, (k + 1) ways)
  // The valid way the last access used (an index: the cache may be copied); kNoWay after
  // invalidate_all.
  static constexpr size_t kNoWay = ~size_t{0};
  size_t mru_ = kNoWay;
  int n_ways_ = 1;
  int line_bytes_ = 64;
  uint64_t set_mask_ = 0;
  uint64_t uses_ = 0;
};

}  // namespace rastsim
