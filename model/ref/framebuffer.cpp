// SPDX-License-Identifier: Apache-2.0
#include "ref/framebuffer.h"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace rastsim {

namespace {

static_assert(sizeof(z_off_t) >= 8, "crc32_combine_gen needs 64-bit lengths for large framebuffers");

// The CRC-32 of n repeats of one 4-byte pixel appended to a running CRC, by doubling:
// crc(P^(2^i)) for every i and the combine operator of each length 4 x 2^i, so a run of
// any length costs one crc32_combine_op per set bit of n.
class RepeatedPixelCrc {
 public:
  explicit RepeatedPixelCrc(const uint8_t px[4]) {
    pow_crc_[0] = crc32(0L, px, 4);
    for (int i = 0; i < kBits; ++i) {
      op_[i] = crc32_combine_gen(static_cast<z_off_t>(uint64_t{4} << i));
      if (i + 1 < kBits) pow_crc_[i + 1] = crc32_combine_op(pow_crc_[i], pow_crc_[i], op_[i]);
    }
  }
  uLong append(uLong crc, uint64_t n) const {
    for (int i = 0; n != 0; ++i, n >>= 1)
      if (n & 1) crc = crc32_combine_op(crc, pow_crc_[i], op_[i]);
    return crc;
  }

 private:
  static constexpr int kBits = 48;  // runs of up to 2^48 pixels
  uLong pow_crc_[kBits] = {}, op_[kBits] = {};
};

// The parallel pipeline (region_bins.h) writes each storage tile from one thread only,
// but the lists of allocated tiles are shared: their appends are serialised (once a tile).
std::mutex touched_mutex;

}  // namespace

Framebuffer::Framebuffer(int w, int h, int s, int tile_log2) : width(w), height(h), samples(s), tile_log2_(tile_log2) {
  if (w < 0 || h < 0 || s < 1 || tile_log2 < 0 || tile_log2 > 12)
    throw std::invalid_argument("Framebuffer: bad size, sample count or tile size");
  const int t = 1 << tile_log2_;
  tiles_x_ = (w + t - 1) / t;
  tiles_y_ = (h + t - 1) / t;
  color_.resize(size_t(tiles_x_) * size_t(tiles_y_));
  depth_.resize(color_.size());
}

Framebuffer::Framebuffer(const Framebuffer& o)
    : width(o.width), height(o.height), samples(o.samples), tile_log2_(o.tile_log2_), tiles_x_(o.tiles_x_),
      tiles_y_(o.tiles_y_), clear_z_(o.clear_z_), color_(o.color_.size()), depth_(o.depth_.size()),
      color_touched_(o.color_touched_), depth_touched_(o.depth_touched_) {
  std::memcpy(clear_rgba_, o.clear_rgba_, 4);
  const size_t n = tile_samples();
  for (uint32_t i : color_touched_) {
    color_[i] = std::make_unique_for_overwrite<uint8_t[]>(n * 4);
    std::memcpy(color_[i].get(), o.color_[i].get(), n * 4);
  }
  for (uint32_t i : depth_touched_) {
    depth_[i] = std::make_unique_for_overwrite<uint32_t[]>(n);
    std::memcpy(depth_[i].get(), o.depth_[i].get(), n * sizeof(uint32_t));
  }
}

Framebuffer& Framebuffer::operator=(const Framebuffer& o) {
  if (this != &o) *this = Framebuffer(o);
  return *this;
}

uint8_t* Framebuffer::alloc_color_tile(size_t i) {
  const size_t n = tile_samples();
  auto t = std::make_unique_for_overwrite<uint8_t[]>(n * 4);
  uint32_t px;
  std::memcpy(&px, clear_rgba_, 4);
  uint8_t* p = t.get();
  for (size_t k = 0; k < n; ++k) std::memcpy(p + k * 4, &px, 4);
  color_[i] = std::move(t);
  const std::lock_guard<std::mutex> lock(touched_mutex);
  color_touched_.push_back(uint32_t(i));
  return p;
}

uint32_t* Framebuffer::alloc_depth_tile(size_t i) {
  const size_t n = tile_samples();
  auto t = std::make_unique_for_overwrite<uint32_t[]>(n);
  std::fill_n(t.get(), n, clear_z_);
  uint32_t* p = t.get();
  depth_[i] = std::move(t);
  const std::lock_guard<std::mutex> lock(touched_mutex);
  depth_touched_.push_back(uint32_t(i));
  return p;
}

void Framebuffer::clear_color(uint8_t r, uint8_t g, uint8_t b) {
  for (uint32_t i : color_touched_) color_[i].reset();
  color_touched_.clear();
  clear_rgba_[0] = r;
  clear_rgba_[1] = g;
  clear_rgba_[2] = b;
  clear_rgba_[3] = 255;
}

void Framebuffer::clear_depth(uint32_t z) {
  for (uint32_t i : depth_touched_) depth_[i].reset();
  depth_touched_.clear();
  clear_z_ = z;
}

void Framebuffer::read_row(int y, uint8_t* out) const {
  const int t = 1 << tile_log2_, ty = y >> tile_log2_, r = y & (t - 1);
  const size_t S = size_t(samples);
  for (int tx = 0; tx < tiles_x_; ++tx) {
    const int x0 = tx * t, n = std::min(t, width - x0);
    uint8_t* o = out + size_t(x0) * 4;
    const uint8_t* tile = color_[size_t(ty) * tiles_x_ + tx].get();
    if (!tile) {
      for (int k = 0; k < n; ++k) std::memcpy(o + size_t(k) * 4, clear_rgba_, 4);
    } else {
      const uint8_t* src = tile + (size_t(r) << tile_log2_) * S * 4;
      if (S == 1)
        std::memcpy(o, src, size_t(n) * 4);
      else
        for (int k = 0; k < n; ++k) std::memcpy(o + size_t(k) * 4, src + size_t(k) * S * 4, 4);
    }
  }
}

void Framebuffer::write_row(int y, const uint8_t* rgba, bool all_samples) {
  for (int x = 0; x < width; ++x)
    for (int s = 0; s < (all_samples ? samples : 1); ++s) std::memcpy(sample(x, y, s), rgba + size_t(x) * 4, 4);
}

Framebuffer Framebuffer::resolve() const {
  if (samples == 1) return *this;
  Framebuffer out(width, height, 1, tile_log2_);
  std::memcpy(out.clear_rgba_, clear_rgba_, 4);  // S equal samples average to themselves
  out.clear_z_ = clear_z_;
  const size_t pixels = size_t(1) << (2 * tile_log2_), S = size_t(samples);
  const unsigned n = unsigned(samples);
  for (uint32_t i : color_touched_) {
    const uint8_t* src = color_[i].get();
    uint8_t* dst = out.alloc_color_tile(i);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (size_t s = 0; s < S; ++s) sum += src[(p * S + s) * 4 + size_t(c)];
        dst[p * 4 + size_t(c)] = static_cast<uint8_t>((sum + n / 2) / n);
      }
  }
  for (uint32_t i : depth_touched_) {
    const uint32_t* src = depth_[i].get();
    uint32_t* dst = out.alloc_depth_tile(i);
    for (size_t p = 0; p < pixels; ++p) dst[p] = src[p * S];
  }
  return out;
}

uint32_t Framebuffer::color_crc32() const {
  if (samples > 1) return resolve().color_crc32();
  const RepeatedPixelCrc clear_run(clear_rgba_);
  std::vector<uint8_t> band(size_t(tiles_y_), 0);  // tile rows holding an allocated tile
  for (uint32_t i : color_touched_) band[i / uint32_t(tiles_x_)] = 1;
  const int t = 1 << tile_log2_;
  uLong crc = crc32(0L, Z_NULL, 0);
  uint64_t run = 0;  // clear pixels not yet added
  for (int ty = 0; ty < tiles_y_; ++ty) {
    const int rows = std::min(t, height - ty * t);
    if (!band[size_t(ty)]) {
      run += uint64_t(width) * uint64_t(rows);
      continue;
    }
    for (int r = 0; r < rows; ++r)
      for (int tx = 0; tx < tiles_x_; ++tx) {
        const int n = std::min(t, width - tx * t);
        const uint8_t* tile = color_[size_t(ty) * tiles_x_ + tx].get();
        if (!tile) {
          run += uint64_t(n);
          continue;
        }
        if (run) crc = clear_run.append(crc, run), run = 0;
        // libdeflate's CRC-32 is zlib's (same polynomial, same chaining) at several times
        // the speed (carry-less multiply): it was 40 % of a 5,000-triangle render.
        crc = libdeflate_crc32(static_cast<uint32_t>(crc), tile + (size_t(r) << tile_log2_) * 4, size_t(n) * 4);
      }
  }
  if (run) crc = clear_run.append(crc, run);
  return static_cast<uint32_t>(crc);
}

namespace {

// a and b the same size: compares tile by tile; a tile unallocated in both (same tiling)
// compares the clear values only, any other every sample of it.
template <class BothClear, class SameSample>
bool same_tiled(const Framebuffer& a, const Framebuffer& b, BothClear both_clear, SameSample same_sample) {
  if (a.width != b.width || a.height != b.height || a.samples != b.samples) return false;
  const bool same_tiling = a.tile_log2() == b.tile_log2();
  const int t = a.tile_size();
  for (int ty = 0; ty < a.tiles_y(); ++ty)
    for (int tx = 0; tx < a.tiles_x(); ++tx) {
      if (same_tiling) {
        if (const std::optional<bool> eq = both_clear(size_t(ty) * size_t(a.tiles_x()) + size_t(tx))) {
          if (!*eq) return false;
          continue;
        }
      }
      for (int y = ty * t; y < std::min(a.height, (ty + 1) * t); ++y)
        for (int x = tx * t; x < std::min(a.width, (tx + 1) * t); ++x)
          for (int s = 0; s < a.samples; ++s)
            if (!same_sample(x, y, s)) return false;
    }
  return true;
}

}  // namespace

bool Framebuffer::same_color(const Framebuffer& o) const {
  return same_tiled(
      *this, o,
      [&](size_t i) -> std::optional<bool> {
        if (color_[i] || o.color_[i]) return std::nullopt;
        return std::memcmp(clear_rgba_, o.clear_rgba_, 4) == 0;
      },
      [&](int x, int y, int s) { return std::memcmp(sample(x, y, s), o.sample(x, y, s), 4) == 0; });
}

bool Framebuffer::same_depth(const Framebuffer& o) const {
  return same_tiled(
      *this, o,
      [&](size_t i) -> std::optional<bool> {
        if (depth_[i] || o.depth_[i]) return std::nullopt;
        return clear_z_ == o.clear_z_;
      },
      [&](int x, int y, int s) { return depth_at(x, y, s) == o.depth_at(x, y, s); });
}

}  // namespace rastsim
