// SPDX-License-Identifier: Apache-2.0
// The size of hierarchical Z's table (ref/hiz.h, docs/depth-culling.md "The table:
// encoding and update rule"): an entry's bytes and the blocks held on chip. A header of
// its own, inline: HizTable sizes itself by these, and so does the RTL parameter
// exporter (rtlsim/rtl_params.cpp: rast_hiz's Blocks), which is built at configure time
// without rastsim_ref.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "ref/raster_state.h"

namespace rastsim {

// The bounds and layer bounds (2 or 4 of D bits) and the B^2-bit mask, padded to a
// power of two of bytes.
inline int hiz_entry_bytes(HizMode mode, int block, int depth_bits) {
  const int bits = (mode == HizMode::MinMax ? 4 : 2) * depth_bits + block * block;
  return int(std::bit_ceil(unsigned((bits + 7) / 8)));
}

// The blocks of a width x height framebuffer held on chip: the first
// min(blocks, floor(onchip_bytes / entry bytes)) in row-major order.
inline int64_t hiz_onchip_blocks(HizMode mode, int block, int64_t onchip_bytes, int width, int height,
                                 int depth_bits) {
  const int64_t blocks = int64_t((width + block - 1) / block) * ((height + block - 1) / block);
  return std::min<int64_t>(onchip_bytes / hiz_entry_bytes(mode, block, depth_bits), blocks);
}

}  // namespace rastsim
