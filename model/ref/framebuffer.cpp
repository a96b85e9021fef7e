// SPDX-License-Identifier: Apache-2.0
#include "ref/framebuffer.h"

#include <zlib.h>

#include <algorithm>

namespace rastsim {

Framebuffer::Framebuffer(int w, int h, int s)
    : width(w), height(h), samples(s), rgba(size_t(w) * h * s * 4, 0), depth(size_t(w) * h * s, 0) {
  clear_color(0, 0, 0);
}

Framebuffer Framebuffer::resolve() const {
  if (samples == 1) return *this;
  Framebuffer out(width, height);
  const unsigned n = unsigned(samples);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      uint8_t* o = out.pixel(x, y);
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (int s = 0; s < samples; ++s) sum += sample(x, y, s)[c];
        o[c] = static_cast<uint8_t>((sum + n / 2) / n);
      }
      out.depth[size_t(y) * width + x] = depth[sample_index(x, y, 0)];
    }
  return out;
}

void Framebuffer::clear_color(uint8_t r, uint8_t g, uint8_t b) {
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = 255;
  }
}

void Framebuffer::clear_depth(uint32_t z) { std::fill(depth.begin(), depth.end(), z); }

uint32_t Framebuffer::color_crc32() const {
  if (samples > 1) return resolve().color_crc32();
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths; feed row by row.
  for (int y = 0; y < height; ++y)
    crc = crc32(crc, rgba.data() + size_t(y) * width * 4, static_cast<uInt>(width * 4));
  return static_cast<uint32_t>(crc);
}

}  // namespace rastsim
