// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/surface_layout.h"

namespace rastsim {

bool SurfaceLayout::sample_at(uint64_t offset, int& x, int& y, int& s) const {
  if (offset >= footprint_bytes()) return false;
  const uint64_t k = offset / uint64_t(bytes_per_sample_);
  s = int(k % uint64_t(samples_));
  const uint64_t p = k / uint64_t(samples_);
  if (layout_ == FbLayout::Linear) {
    x = int(p % uint64_t(width_));
    y = int(p / uint64_t(width_));
    return true;
  }
  const uint64_t tile = p >> (tw_log2_ + th_log2_), in_tile = p & ((uint64_t{1} << (tw_log2_ + th_log2_)) - 1);
  x = int((tile % uint64_t(tiles_x_)) << tw_log2_) + int(in_tile & ((uint64_t{1} << tw_log2_) - 1));
  y = int((tile / uint64_t(tiles_x_)) << th_log2_) + int(in_tile >> tw_log2_);
  return x < width_ && y < height_;
}

}  // namespace rastsim
