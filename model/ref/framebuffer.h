// SPDX-License-Identifier: Apache-2.0
// Framebuffer: RGBA8 colour and unorm depth, row 0 at the top; its CRC.
// (Image files: display/image_io.h.)
//
// With raster.samples = S > 1 every pixel holds S colour and S depth samples, stored
// sample after sample within a pixel (pixel (x, y) sample s at index (y W + x) S + s).
// resolve() box-filters them to a one-sample framebuffer: each channel is the average of
// the S samples rounded half up, (sum + S/2) / S. The image, the CRC and scan-out see the
// resolved buffer; pixel() of a multisampled buffer is its sample 0.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rastsim {

struct Framebuffer {
  int width = 0, height = 0;
  int samples = 1;              // colour and depth samples a pixel
  std::vector<uint8_t> rgba;    // 4 bytes a sample, R G B A, rows top to bottom
  std::vector<uint32_t> depth;  // one unorm value a sample

  Framebuffer() = default;
  Framebuffer(int w, int h, int samples = 1);
  size_t sample_index(int x, int y, int s) const { return (size_t(y) * width + x) * samples + s; }
  uint8_t* sample(int x, int y, int s) { return &rgba[sample_index(x, y, s) * 4]; }
  const uint8_t* sample(int x, int y, int s) const { return &rgba[sample_index(x, y, s) * 4]; }
  // The box-filtered one-sample buffer (colour; depth is sample 0's). A copy for S = 1.
  Framebuffer resolve() const;
  void clear_color(uint8_t r, uint8_t g, uint8_t b);
  void clear_depth(uint32_t z);
  uint8_t* pixel(int x, int y) { return &rgba[sample_index(x, y, 0) * 4]; }
  const uint8_t* pixel(int x, int y) const { return &rgba[sample_index(x, y, 0) * 4]; }

  // CRC-32 (IEEE, as zlib) of the RGBA8 colour buffer, rows top to bottom; of the
  // resolved buffer when samples > 1.
  uint32_t color_crc32() const;
};

}  // namespace rastsim
