// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/cache.h"

#include <bit>
#include <stdexcept>

namespace rastsim {

SetAssocCache::SetAssocCache(const CacheParams& p) : n_ways_(p.ways), line_bytes_(p.line_bytes) {
  const uint64_t way_bytes = uint64_t(p.ways) * uint64_t(p.line_bytes);
  if (p.bytes == 0 || p.ways < 1 || p.line_bytes < 1 || p.bytes % way_bytes != 0 ||
      !std::has_single_bit(p.bytes / way_bytes) || !std::has_single_bit(unsigned(p.line_bytes)))
    throw std::invalid_argument("SetAssocCache: bytes must be ways x line_bytes x a power of two");
  set_mask_ = p.bytes / way_bytes - 1;
  ways_.resize(size_t(p.bytes / uint64_t(p.line_bytes)));
}

bool SetAssocCache::access_set(uint64_t line, bool write, Victim& victim) {
  Way* set = &ways_[size_t(line & set_mask_) * size_t(n_ways_)];
  ++uses_;
  Way* lru = set;
  for (int i = 0; i < n_ways_; ++i) {
    Way& w = set[i];
    if (w.valid && w.line == line) {
      w.last_use = uses_;
      w.dirty = w.dirty || write;
      mru_ = size_t(&w - ways_.data());
      return true;
    }
    // An invalid way first (last_use 0 never wins against a used way otherwise).
    if (!w.valid ? lru->valid : (lru->valid && w.last_use < lru->last_use)) lru = &w;
  }
  victim = {lru->valid, lru->valid && lru->dirty, lru->line};
  *lru = {line, uses_, true, write};
  mru_ = size_t(lru - ways_.data());
  return false;
}

bool SetAssocCache::holds(uint64_t line) const {
  const Way* set = &ways_[size_t(line & set_mask_) * size_t(n_ways_)];
  for (int i = 0; i < n_ways_; ++i)
    if (set[i].valid && set[i].line == line) return true;
  return false;
}

void SetAssocCache::invalidate_all() {
  for (Way& w : ways_) w = Way{};
  mru_ = kNoWay;
}

}  // namespace rastsim
