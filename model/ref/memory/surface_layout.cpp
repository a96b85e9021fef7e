// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/surface_layout.h"

#include <bit>
#include <cstdint>

namespace rastsim {

namespace {

// a / d and a % d for d > 0: a shift and a mask when d is a power of two (the bytes a
// sample and the samples a pixel always are, on the shipped configs), a 32-bit division
// when both fit, else a 64-bit one. Same results; sample_at runs on every ROP cache miss
// and write-back, and its 64-bit divisions were 70 % of its time (perf, the reference
// pass on the torus sequence).
struct QuotRem {
  uint64_t q, r;
};
// (d & (d - 1)) == 0 rather than std::has_single_bit: without -mpopcnt that is a libgcc
// call (__popcountdi2, 4 % of the reference pass when it was used here).
inline QuotRem quot_rem(uint64_t a, uint64_t d) {
  if ((d & (d - 1)) == 0) return {a >> std::countr_zero(d), a & (d - 1)};
  if (a <= UINT32_MAX && d <= UINT32_MAX) {
    const uint32_t q = uint32_t(a) / uint32_t(d);
    return {q, a - uint64_t(q) * d};
  }
  return {a / d, a % d};
}

}  // namespace

bool SurfaceLayout::sample_at(uint64_t offset, int& x, int& y, int& s) const {
  if (offset >= footprint_bytes()) return false;
  const uint64_t k = quot_rem(offset, uint64_t(bytes_per_sample_)).q;
  const QuotRem ps = quot_rem(k, uint64_t(samples_));  // pixel p, sample s
  s = int(ps.r);
  const uint64_t p = ps.q;
  if (layout_ == FbLayout::Linear) {
    const QuotRem yx = quot_rem(p, uint64_t(width_));
    x = int(yx.r);
    y = int(yx.q);
    return true;
  }
  const uint64_t tile = p >> (tw_log2_ + th_log2_), in_tile = p & ((uint64_t{1} << (tw_log2_ + th_log2_)) - 1);
  const QuotRem t = quot_rem(tile, uint64_t(tiles_x_));  // tile row, tile column
  x = int(t.r << tw_log2_) + int(in_tile & ((uint64_t{1} << tw_log2_) - 1));
  y = int(t.q << th_log2_) + int(in_tile >> tw_log2_);
  return x < width_ && y < height_;
}

}  // namespace rastsim
