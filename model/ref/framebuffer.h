// SPDX-License-Identifier: Apache-2.0
// Framebuffer: RGBA8 colour and unorm depth, row 0 at the top; its CRC.
// (Image files: display/image_io.h.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rastsim {

struct Framebuffer {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;    // 4 bytes a pixel, R G B A, rows top to bottom
  std::vector<uint32_t> depth;  // one unorm value a pixel

  Framebuffer() = default;
  Framebuffer(int w, int h);
  void clear_color(uint8_t r, uint8_t g, uint8_t b);
  void clear_depth(uint32_t z);
  uint8_t* pixel(int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; }
  const uint8_t* pixel(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }

  // CRC-32 (IEEE, as zlib) of the RGBA8 colour buffer, rows top to bottom.
  uint32_t color_crc32() const;
};

}  // namespace rastsim
