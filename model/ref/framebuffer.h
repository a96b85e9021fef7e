// SPDX-License-Identifier: Apache-2.0
// Framebuffer: RGBA8 colour and unorm depth, row 0 at the top; CRC and image files.
#pragma once

#include <cstdint>
#include <string>
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

// Writes the colour buffer as PNG (RGB, alpha dropped since it is always 255) or binary
// PPM, chosen by the extension. Throws std::runtime_error naming the file on failure.
void write_image(const Framebuffer& fb, const std::string& path);
// Reads a PNG or PPM written by write_image back into RGBA8 (for tests and tools).
Framebuffer read_image(const std::string& path);

}  // namespace rastsim
