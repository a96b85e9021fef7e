// SPDX-License-Identifier: Apache-2.0
// Framebuffer: RGBA8 colour and unorm depth, row 0 at the top; its CRC.
// (Image files: image/image_io.h.)
//
// With raster.samples = S > 1 every pixel holds S colour and S depth samples. resolve()
// box-filters them to a one-sample framebuffer: each channel is the average of the S
// samples rounded half up, (sum + S/2) / S. The image, the CRC and scan-out see the
// resolved buffer; pixel() of a multisampled buffer is its sample 0.
//
// Sparse storage (docs/framebuffer.md): colour and depth are each kept in square tiles of
// T x T pixels (T = 2^tile_log2, 32 by default), S samples a pixel, allocated on their
// first write. A tile never written since the last clear is not stored at all: every one
// of its samples reads as the clear value. A clear frees the tiles written since the
// previous one, so it costs what was drawn, not the screen; color_crc32() runs over the
// untouched tiles without materialising them (CRC-combine of runs of the clear pixel),
// and read_row() fills them in. Colour and depth are separate: a colour clear leaves the
// depth tiles as they are, and the other way round.
//
// Access: the const pixel()/sample()/depth_at() read and never allocate; the non-const
// pixel()/sample() return a writable pointer and allocate the tile (write access), as
// does set_depth(). A pointer stays valid until the next clear, resolve or assignment.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace rastsim {

// The largest image extent anything names, px (or lines): a framebuffer side
// (display.width, display.height), a video mode's active size and blanking, a trace's
// viewport and scissor. Small enough that x + width never overflows an int.
inline constexpr int kMaxImageExtent = 16384;

class Framebuffer {
 public:
  static constexpr int kDefaultTileLog2 = 5;  // 32 x 32 pixel tiles

  // Read only (public for the many readers of the size); set by the constructor.
  int width = 0, height = 0;
  int samples = 1;  // colour and depth samples a pixel

  Framebuffer() = default;
  // Colour cleared to opaque black (0, 0, 0, 255), depth to 0.
  Framebuffer(int w, int h, int samples = 1, int tile_log2 = kDefaultTileLog2);
  Framebuffer(const Framebuffer& o);
  Framebuffer& operator=(const Framebuffer& o);
  Framebuffer(Framebuffer&&) noexcept = default;
  Framebuffer& operator=(Framebuffer&&) noexcept = default;
  ~Framebuffer() = default;

  int tile_log2() const { return tile_log2_; }
  int tile_size() const { return 1 << tile_log2_; }

  // Colour of sample s of pixel (x, y), 4 bytes R G B A. Const: reads (the clear colour
  // for an untouched tile); non-const: for writing, allocates the tile.
  const uint8_t* sample(int x, int y, int s) const {
    const uint8_t* t = color_[tile_index(x, y)].get();
    return t ? t + in_tile(x, y, s) * 4 : clear_rgba_;
  }
  uint8_t* sample(int x, int y, int s) { return color_tile(tile_index(x, y)) + in_tile(x, y, s) * 4; }
  const uint8_t* pixel(int x, int y) const { return sample(x, y, 0); }
  uint8_t* pixel(int x, int y) { return sample(x, y, 0); }

  // Depth of sample s of pixel (x, y); set_depth allocates the depth tile.
  uint32_t depth_at(int x, int y, int s = 0) const {
    const uint32_t* t = depth_[tile_index(x, y)].get();
    return t ? t[in_tile(x, y, s)] : clear_z_;
  }
  void set_depth(int x, int y, int s, uint32_t z) { depth_tile(tile_index(x, y))[in_tile(x, y, s)] = z; }

  // Runs of a one-sample buffer (samples == 1; the ROP's runs, rop.h rop_write_run): the
  // pixels from (x, y) to the right edge of its storage tile, tile_end_x(x), lie one after
  // another, 4 colour bytes or one depth value each. color_run and depth_run are for
  // writing (they allocate the tile, as sample() and set_depth() do); stored_depth_run
  // reads, and is null for a tile not stored, whose every depth is cleared_depth().
  int tile_end_x(int x) const { return std::min(width, ((x >> tile_log2_) + 1) << tile_log2_); }
  uint8_t* color_run(int x, int y) { return sample(x, y, 0); }
  uint32_t* depth_run(int x, int y) { return depth_tile(tile_index(x, y)) + in_tile(x, y, 0); }
  const uint32_t* stored_depth_run(int x, int y) const {
    const uint32_t* t = depth_[tile_index(x, y)].get();
    return t ? t + in_tile(x, y, 0) : nullptr;
  }
  uint32_t cleared_depth() const { return clear_z_; }

  // Row y's colour, sample 0 of each pixel, as width x 4 bytes RGBA into `out` (the
  // image row of a one-sample buffer); untouched tiles read as the clear colour.
  void read_row(int y, uint8_t* out) const;
  // Sets row y's colour (sample 0 of each pixel; every sample when `all_samples`) from
  // width x 4 bytes RGBA.
  void write_row(int y, const uint8_t* rgba, bool all_samples = false);

  // The box-filtered one-sample buffer (colour; depth is sample 0's), tile by tile: an
  // untouched tile resolves to the clear colour and stays unallocated. A copy for S = 1.
  Framebuffer resolve() const;
  // Fill the colour buffer with (r, g, b, 255) / the depth buffer with z. Frees the tiles
  // written since the previous clear: O(those tiles), not O(pixels).
  void clear_color(uint8_t r, uint8_t g, uint8_t b);
  void clear_depth(uint32_t z);

  // CRC-32 (IEEE, as zlib) of the RGBA8 colour buffer, rows top to bottom; of the
  // resolved buffer when samples > 1. Untouched tiles are runs of the clear pixel, added
  // by CRC-combine without being materialised.
  uint32_t color_crc32() const;

  // Same colour (every sample) / same depth (every sample), whatever the tiling.
  bool same_color(const Framebuffer& o) const;
  bool same_depth(const Framebuffer& o) const;

  // Tiles allocated now (for tests and the memory figures).
  size_t color_tiles_allocated() const { return color_touched_.size(); }
  size_t depth_tiles_allocated() const { return depth_touched_.size(); }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }

 private:
  size_t tile_index(int x, int y) const { return size_t(y >> tile_log2_) * size_t(tiles_x_) + size_t(x >> tile_log2_); }
  size_t in_tile(int x, int y, int s) const {
    const int m = (1 << tile_log2_) - 1;
    return ((size_t(y & m) << tile_log2_) + size_t(x & m)) * size_t(samples) + size_t(s);
  }
  size_t tile_samples() const { return (size_t(1) << (2 * tile_log2_)) * size_t(samples); }
  uint8_t* color_tile(size_t i) {
    uint8_t* t = color_[i].get();
    return t ? t : alloc_color_tile(i);
  }
  uint32_t* depth_tile(size_t i) {
    uint32_t* t = depth_[i].get();
    return t ? t : alloc_depth_tile(i);
  }
  uint8_t* alloc_color_tile(size_t i);
  uint32_t* alloc_depth_tile(size_t i);

  int tile_log2_ = kDefaultTileLog2;
  int tiles_x_ = 0, tiles_y_ = 0;
  uint8_t clear_rgba_[4] = {0, 0, 0, 255};
  uint32_t clear_z_ = 0;
  std::vector<std::unique_ptr<uint8_t[]>> color_;   // tiles_x x tiles_y, null = clear
  std::vector<std::unique_ptr<uint32_t[]>> depth_;
  std::vector<uint32_t> color_touched_, depth_touched_;  // the allocated tiles' indices
};

}  // namespace rastsim
