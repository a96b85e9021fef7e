// SPDX-License-Identifier: Apache-2.0
// rop.depth_compression = "plane": the encoding of one depth block (the fast-clear block,
// rop.fast_clear_block_width x _height pixels, S samples a pixel, depth D =
// raster.depth_bits bits), counted in exact bytes. The framebuffer is unchanged: the
// encoding is lossless and only the bytes moved change (docs/memory.md).
//
// A plane block stores
//   anchor a = z(0, 0, sample 0)                      D bits, unsigned
//   slopes dx = z(1, 0, 0) - a, dy = z(0, 1, 0) - a   D + 1 bits each, two's complement
//                                                     (0 where the block is 1 wide / high)
//   residual r(i, j, s) = z(i, j, s) - (a + dx i + dy j), for every pixel (i, j) of the
//                                                     block and sample s, kPlaneResidualBits
//                                                     bits each, two's complement
// (i, j: the pixel's column and row in the block), so
//   plane bytes = ceil((D + 2 (D + 1) + kPlaneResidualBits bw bh S) / 8).
// A block is stored so when every residual fits and the plane bytes are fewer than the
// raw block's (bw bh S bytes-per-sample); else raw. A depth interp.method = plane gives is
// the triangle's plane rounded at the pixel, and slopes from rounded neighbours are off by
// less than one, so a one-sample 8 x 8 block inside one triangle always fits 5 bits
// (|r| < 1 + 7 + 7).
// Pixels of an edge block outside the surface store residual 0.
#pragma once

#include <cstdint>

namespace rastsim {

inline constexpr int kPlaneResidualBits = 5;

// The bytes of a plane-encoded block.
inline uint64_t plane_block_bytes(int block_width, int block_height, int samples, int depth_bits) {
  const uint64_t bits = uint64_t(depth_bits) + 2 * uint64_t(depth_bits + 1) +
                        uint64_t(kPlaneResidualBits) * uint64_t(block_width) * uint64_t(block_height) * uint64_t(samples);
  return (bits + 7) / 8;
}

// True when the block's depths z(i, j, s) (i < w, j < h: the block's pixels inside the
// surface; s < samples) fit the plane encoding's residuals.
template <class DepthAt>
bool fits_plane(int w, int h, int samples, DepthAt&& z) {
  const int64_t a = z(0, 0, 0);
  const int64_t dx = w > 1 ? int64_t(z(1, 0, 0)) - a : 0, dy = h > 1 ? int64_t(z(0, 1, 0)) - a : 0;
  constexpr int64_t lo = -(int64_t{1} << (kPlaneResidualBits - 1)), hi = (int64_t{1} << (kPlaneResidualBits - 1)) - 1;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int s = 0; s < samples; ++s) {
        const int64_t r = int64_t(z(i, j, s)) - (a + dx * i + dy * j);
        if (r < lo || r > hi) return false;
      }
  return true;
}

}  // namespace rastsim
