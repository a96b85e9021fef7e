// SPDX-License-Identifier: Apache-2.0
// Where a framebuffer surface's samples lie in memory (docs/memory.md, "Framebuffer,
// caches, fast clear and compression").
//
// A surface is width x height pixels of `samples` samples, bytes_per_sample bytes each,
// from byte address `base`. The samples of a pixel lie one after another, sample 0 first,
// as the Framebuffer stores them. Pixels:
// - linear: row-major over the whole surface,
//     address = base + ((y W + x) S + s) B
// - tiled: tiles of tile_width x tile_height pixels (powers of two), the tiles row-major
//   over the surface (tiles_x = ceil(W / tile_width) a row; the edge tiles padded to the
//   whole tile), the pixels row-major within a tile:
//     address = base + (((ty tiles_x + tx) tw th + (y mod th) tw + (x mod tw)) S + s) B
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "ref/memory/memory_params.h"

namespace rastsim {

// Bytes of one stored sample: colour RGBA8 = 4; depth = 2 for raster.depth_bits <= 16,
// else 4 (24-bit depth kept in 32 bits, as D24 formats are).
inline constexpr int kColorBytesPerSample = 4;
inline int depth_bytes_per_sample(int depth_bits) { return depth_bits <= 16 ? 2 : 4; }

class SurfaceLayout {
 public:
  SurfaceLayout() = default;
  // Inline, as the config's checks use it (config/memory_config.cpp) and the RTL
  // parameter exporter builds the config sources without this library.
  SurfaceLayout(FbLayout layout, int tile_width, int tile_height, uint64_t base, int width, int height, int samples,
                int bytes_per_sample)
      : layout_(layout), tw_log2_(std::countr_zero(unsigned(tile_width))),
        th_log2_(std::countr_zero(unsigned(tile_height))), base_(base), width_(width), height_(height),
        samples_(samples), bytes_per_sample_(bytes_per_sample) {
    if (!std::has_single_bit(unsigned(tile_width)) || !std::has_single_bit(unsigned(tile_height)) || width < 0 ||
        height < 0 || samples < 1 || bytes_per_sample < 1)
      throw std::invalid_argument("SurfaceLayout: tile sides must be powers of two, sizes positive");
    tiles_x_ = (width + tile_width - 1) >> tw_log2_;
    tiles_y_ = (height + tile_height - 1) >> th_log2_;
  }

  // Byte address of sample s of pixel (x, y).
  uint64_t address_of(int x, int y, int s) const { return base_ + offset_of(x, y, s); }
  // Byte offset from base of sample s of pixel (x, y).
  uint64_t offset_of(int x, int y, int s) const {
    uint64_t p;
    if (layout_ == FbLayout::Linear) {
      p = uint64_t(y) * uint64_t(width_) + uint64_t(x);
    } else {
      const uint64_t tile = uint64_t(y >> th_log2_) * uint64_t(tiles_x_) + uint64_t(x >> tw_log2_);
      const uint64_t in_tile = (uint64_t(y & ((1 << th_log2_) - 1)) << tw_log2_) + uint64_t(x & ((1 << tw_log2_) - 1));
      p = (tile << (tw_log2_ + th_log2_)) + in_tile;
    }
    return (p * uint64_t(samples_) + uint64_t(s)) * uint64_t(bytes_per_sample_);
  }
  // The pixel and sample stored at byte offset `offset` (any byte of the sample); false
  // for padding (a tiled surface's edge tiles beyond the surface, or past its end).
  bool sample_at(uint64_t offset, int& x, int& y, int& s) const;

  // f(x, y, s, n) for every run of n > 0 samples stored one after another in the bytes
  // [offset, offset + len), in address order, padding skipped: sample s of pixel (x, y)
  // and the n - 1 after it along row y (s counting up to samples, then the next pixel),
  // never past the row's (linear) or the tile row's (tiled) end or the surface's right
  // edge; stops early when f returns false. One sample_at a run, not one a sample.
  template <class F>
  void for_each_run(uint64_t offset, uint64_t len, F&& f) const {
    const uint64_t bpp = uint64_t(bytes_per_sample_);
    uint64_t k = offset / bpp;
    const uint64_t k_end = (offset + len + bpp - 1) / bpp;
    while (k < k_end) {
      int x, y, s;
      if (!sample_at(k * bpp, x, y, s)) {
        ++k;
        continue;
      }
      const int run_end = layout_ == FbLayout::Linear ? width_ : std::min(width_, (x | ((1 << tw_log2_) - 1)) + 1);
      const uint64_t n = std::min(k_end - k, uint64_t(run_end - x) * uint64_t(samples_) - uint64_t(s));
      if (!f(x, y, s, n)) return;
      k += n;
    }
  }
  // f(x, y, s) for every sample of for_each_run's runs, in address order; stops early
  // when f returns false.
  template <class F>
  void for_each_sample(uint64_t offset, uint64_t len, F&& f) const {
    for_each_run(offset, len, [&](int x, int y, int s, uint64_t n) {
      for (; n > 0; --n) {
        if (!f(x, y, s)) return false;
        if (++s == samples_) s = 0, ++x;
      }
      return true;
    });
  }

  uint64_t base() const { return base_; }
  // Bytes from base to the end of the last stored sample (padding included).
  uint64_t footprint_bytes() const {
    const uint64_t pixels = layout_ == FbLayout::Linear
                                ? uint64_t(width_) * uint64_t(height_)
                                : (uint64_t(tiles_x_) * uint64_t(tiles_y_)) << (tw_log2_ + th_log2_);
    return pixels * uint64_t(samples_) * uint64_t(bytes_per_sample_);
  }
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  int bytes_per_sample() const { return bytes_per_sample_; }

 private:
  FbLayout layout_ = FbLayout::Linear;
  int tw_log2_ = 0, th_log2_ = 0;
  uint64_t base_ = 0;
  int width_ = 0, height_ = 0, samples_ = 1, bytes_per_sample_ = 4;
  int tiles_x_ = 0, tiles_y_ = 0;
};

}  // namespace rastsim
