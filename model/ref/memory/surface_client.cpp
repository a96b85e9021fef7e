// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/surface_client.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <utility>

#include "ref/framebuffer.h"
#include "ref/memory/depth_compression.h"

namespace rastsim {

SurfaceClient::SurfaceClient(const SurfaceLayout& layout, const CacheParams& cache, bool fast_clear, int block_width,
                             int block_height)
    : layout_(layout), fast_clear_(fast_clear), block_w_(block_width), block_h_(block_height),
      blocks_x_((layout.width() + block_width - 1) / block_width),
      blocks_y_((layout.height() + block_height - 1) / block_height),
      flagged_(size_t(blocks_x_) * size_t(blocks_y_), 0) {
  if (cache.bytes > 0) {
    cache_.emplace(cache);
    line_shift_ = std::countr_zero(unsigned(cache_->line_bytes()));
  }
}

void SurfaceClient::compress_planes(const Framebuffer* fb, int depth_bits) {
  fb_ = fb;
  depth_bits_ = depth_bits;
  plane_stored_.assign(flagged_.size(), 0);
}

uint64_t SurfaceClient::block_bytes(size_t block) const {
  const int x0 = int(block % size_t(blocks_x_)) * block_w_, y0 = int(block / size_t(blocks_x_)) * block_h_;
  const uint64_t w = uint64_t(std::min(block_w_, layout_.width() - x0)), h = uint64_t(std::min(block_h_, layout_.height() - y0));
  return w * h * uint64_t(layout_.samples()) * uint64_t(layout_.bytes_per_sample());
}

void SurfaceClient::cached_miss(uint64_t line, const SetAssocCache::Victim& victim) {
  ++stats_.misses;
  if (victim.valid) ++stats_.evictions;
  if (victim.dirty) {
    ++stats_.writebacks;
    if (fb_) write_back_block(victim.line);
    else write_back_range(victim.line * uint64_t(cache_->line_bytes()), uint64_t(cache_->line_bytes()));
  }
  const uint64_t line_offset = line * uint64_t(cache_->line_bytes());
  if (fb_) {  // a compressed surface's line is one block
    if (!flagged_[line])
      fill(line_offset, plane_stored_[line] ? plane_block_bytes(block_w_, block_h_, layout_.samples(), depth_bits_)
                                            : uint64_t(cache_->line_bytes()));
  } else {
    fill(line_offset, fill_range_bytes(line_offset, uint64_t(cache_->line_bytes())));
  }
}

// f(block, samples) for each piece of the bytes [offset, offset + len) that lies in one
// fast-clear block, in address order (a run of a row cut at the blocks' edges); stops
// early when f returns false.
// The blocks' sides are powers of two on every shipped config: a shift then, not a
// division (the divisions were a fifth of write_back_range's time, perf on the torus).
template <class F>
void SurfaceClient::for_each_block_piece(uint64_t offset, uint64_t len, F&& f) const {
  const int samples = layout_.samples();
  const bool pow2 = (block_w_ & (block_w_ - 1)) == 0 && (block_h_ & (block_h_ - 1)) == 0;  // both > 0
  const int w_log2 = std::countr_zero(unsigned(block_w_)), h_log2 = std::countr_zero(unsigned(block_h_));
  layout_.for_each_run(offset, len, [&](int x, int y, int s, uint64_t n) {
    const size_t row = size_t(pow2 ? y >> h_log2 : y / block_h_) * size_t(blocks_x_);
    for (int bx = pow2 ? x >> w_log2 : x / block_w_; n > 0; ++bx) {
      // The samples from (x, s) to the block's right edge, at most the run's rest.
      const uint64_t m = std::min(n, uint64_t((bx + 1) * block_w_ - x) * uint64_t(samples) - uint64_t(s));
      if (!f(row + size_t(bx), m)) return false;
      n -= m, x = (bx + 1) * block_w_, s = 0;
    }
    return true;
  });
}

bool SurfaceClient::range_all_flagged(uint64_t offset, uint64_t len) const {
  bool all = true;
  for_each_block_piece(offset, len, [&](size_t b, uint64_t) { return all = flagged_[b] != 0; });
  return all;
}

uint64_t SurfaceClient::fill_range_bytes(uint64_t offset, uint64_t len) const {
  return n_flagged_ > 0 && range_all_flagged(offset, len) ? 0 : len;
}

void SurfaceClient::write_back_range(uint64_t offset, uint64_t len) {
  stats_.bytes_written += len;
  transfer(offset, len, true);
  if (n_flagged_ == 0) return;
  // The flagged blocks the range touches, with the bytes of each inside the range.
  std::vector<std::pair<size_t, uint64_t>>& touched = touched_;
  touched.clear();
  const uint64_t step = uint64_t(layout_.bytes_per_sample());
  for_each_block_piece(offset, len, [&](size_t b, uint64_t samples) {
    if (!flagged_[b]) return true;
    if (!touched.empty() && touched.back().first == b) touched.back().second += samples * step;
    else {
      auto it = std::find_if(touched.begin(), touched.end(), [&](const auto& t) { return t.first == b; });
      if (it == touched.end()) touched.push_back({b, samples * step});
      else it->second += samples * step;
    }
    return true;
  });
  for (const auto& [b, inside] : touched) {
    flagged_[b] = 0;
    --n_flagged_;
    const uint64_t fill = block_bytes(b) - inside;
    stats_.bytes_written += fill;
    stats_.clear_fill_bytes += fill;
    // Posted from the block's first sample (in a linear layout the block's rows outside
    // the line are not one range; the model sends them as one write).
    const int x0 = int(b % size_t(blocks_x_)) * block_w_, y0 = int(b / size_t(blocks_x_)) * block_h_;
    transfer(layout_.offset_of(x0, y0, 0), fill, true);
  }
}

void SurfaceClient::write_back_block(uint64_t block) {
  if (flagged_[block]) {  // the line is the whole block: nothing else to materialise
    flagged_[block] = 0;
    --n_flagged_;
  }
  const int x0 = int(block % uint64_t(blocks_x_)) * block_w_, y0 = int(block / uint64_t(blocks_x_)) * block_h_;
  const int w = std::min(block_w_, layout_.width() - x0), h = std::min(block_h_, layout_.height() - y0);
  const uint64_t plane = plane_block_bytes(block_w_, block_h_, layout_.samples(), depth_bits_);
  const bool fits = plane < uint64_t(cache_->line_bytes()) &&
                    fits_plane(w, h, layout_.samples(), [&](int i, int j, int s) { return fb_->depth_at(x0 + i, y0 + j, s); });
  plane_stored_[block] = fits;
  const uint64_t offset = block * uint64_t(cache_->line_bytes());  // the block is the line
  if (!fits) {
    stats_.bytes_written += uint64_t(cache_->line_bytes());
    transfer(offset, uint64_t(cache_->line_bytes()), true);
    return;
  }
  stats_.bytes_written += plane;
  transfer(offset, plane, true);
  stats_.compressed_bytes += plane;
  ++stats_.compressed_blocks;
}

void SurfaceClient::take_state(const SurfaceClient& from) {
  if (from.flagged_.size() != flagged_.size() || from.cache_.has_value() != cache_.has_value() ||
      from.layout_.base() != layout_.base() || from.plane_stored_.size() != plane_stored_.size())
    throw std::logic_error("SurfaceClient::take_state: the state of another surface");
  cache_ = from.cache_;
  flagged_ = from.flagged_;
  n_flagged_ = from.n_flagged_;
  plane_stored_ = from.plane_stored_;
  last_x_ = last_y_ = last_s_ = -1;  // the offset cache: recomputed at the next access
}

void SurfaceClient::clear() {
  if (cache_) cache_->invalidate_all();
  const uint64_t blocks = flagged_.size();
  if (fast_clear_) {
    std::fill(flagged_.begin(), flagged_.end(), 1);
    n_flagged_ = blocks;
    stats_.fast_clear_blocks += blocks;
    return;
  }
  std::fill(flagged_.begin(), flagged_.end(), 0);
  n_flagged_ = 0;
  // A constant surface: each block a plane with zero slopes and residuals, when smaller.
  const uint64_t plane = fb_ ? plane_block_bytes(block_w_, block_h_, layout_.samples(), depth_bits_) : 0;
  if (fb_ && plane < uint64_t(cache_->line_bytes())) {
    std::fill(plane_stored_.begin(), plane_stored_.end(), 1);
    stats_.bytes_written += blocks * plane;
    stats_.compressed_bytes += blocks * plane;
    stats_.compressed_blocks += blocks;
    transfer(0, blocks * plane, true);  // the blocks' planes, one stream from the base
    return;
  }
  if (fb_) std::fill(plane_stored_.begin(), plane_stored_.end(), 0);
  const uint64_t bytes = uint64_t(layout_.width()) * uint64_t(layout_.height()) * uint64_t(layout_.samples()) *
                         uint64_t(layout_.bytes_per_sample());
  stats_.bytes_written += bytes;
  transfer(0, bytes, true);
}

void SurfaceClient::write_back_all() {
  if (!cache_) return;
  cache_->write_back_all([&](uint64_t line) {
    ++stats_.writebacks;
    if (fb_) write_back_block(line);
    else write_back_range(line * uint64_t(cache_->line_bytes()), uint64_t(cache_->line_bytes()));
  });
}

}  // namespace rastsim
