// SPDX-License-Identifier: Apache-2.0
#include "ref/binning.h"

#include <algorithm>

#include "ref/homogeneous.h"

namespace rastsim {

Binner::Binner(const RasterState& st, const TraversalParams& tp, Framebuffer& fb, DrawFn draw, BinStats& stats,
               BinMemory* mem)
    : st_(st), tp_(tp), fb_(fb), draw_(std::move(draw)), stats_(stats), mem_(mem) {
  nx_ = (st.fb_width + st.bin.width - 1) / st.bin.width;
  ny_ = (st.fb_height + st.bin.height - 1) / st.bin.height;
  const size_t n = size_t(nx_) * size_t(ny_);
  lists_.resize(n);
  color_stored_.assign(n, 0);
  depth_stored_.assign(n, 0);
  stats_.enabled = true;
  stats_.bins = n;
}

PixelRect Binner::bin_rect(int b) const {
  const int x = (b % nx_) * st_.bin.width, y = (b / nx_) * st_.bin.height;
  return PixelRect{x, y, x + st_.bin.width, y + st_.bin.height}.intersect({0, 0, st_.fb_width, st_.fb_height});
}

PixelRect Binner::bin_range(const PixelRect& box) const {
  if (box.empty()) return {};
  return {box.x0 / st_.bin.width, box.y0 / st_.bin.height, (box.x1 - 1) / st_.bin.width + 1,
          (box.y1 - 1) / st_.bin.height + 1};
}

std::vector<int> Binner::bins_of(const SetupTriangle& tri) const {
  std::vector<int> out;
  const PixelRect range = bin_range(tri.bbox);
  for (int by = range.y0; by < range.y1; ++by)
    for (int bx = range.x0; bx < range.x1; ++bx) {
      const int b = by * nx_ + bx;
      if (st_.bin.rule == BinningRule::Exact) {
        // The raster's own traversal over the box clipped to the bin: listed when it
        // finds a covered sample (its counters are scratch: binning is not drawing).
        SetupTriangle walk = tri;
        walk.bbox = tri.bbox.intersect(bin_rect(b));
        TraversalCounters scratch;
        bool covered = false;
        traverse(walk, tp_, scratch, [&](int, int, uint32_t) { covered = true; });
        if (!covered) continue;
      }
      out.push_back(b);
    }
  return out;
}

// Room for `bytes` more in the parameter buffer: when it is short, an overflow pass
// renders what it holds first. A record that cannot fit an empty buffer is an error.
void Binner::reserve(uint64_t bytes, const SourceLoc& loc) {
  if (bytes > st_.bin.parameter_buffer_bytes)
    throw SceneError(loc.str() + ": a primitive needs " + std::to_string(bytes) +
                     " bytes of parameter buffer (record + bin list entries) and bin.parameter_buffer_bytes is " +
                     std::to_string(st_.bin.parameter_buffer_bytes) + " (docs/binning.md)");
  if (used_ + bytes > st_.bin.parameter_buffer_bytes) {
    ++stats_.bin_overflows;
    render_pass(false);
  }
  used_ += bytes;
  stats_.geometry_bytes_written += bytes;
}

void Binner::add_triangle(const SetupTriangle& tri, const SourceLoc& loc) {
  const std::vector<int> bins = bins_of(tri);
  if (bins.empty()) return;  // exact binning: no covered sample anywhere, nothing to draw
  reserve(kBinPrimitiveRecordBytes + kBinListEntryBytes * bins.size(), loc);
  const auto index = uint32_t(tris_.size());
  tris_.push_back(tri);
  tri_seq_.push_back(seq_++);
  tri_offset_.push_back(record_bytes_);
  if (mem_) mem_->record(record_bytes_, kBinPrimitiveRecordBytes, true);
  record_bytes_ += kBinPrimitiveRecordBytes;
  for (int b : bins) {
    if (mem_) mem_->entry(entries_, true);
    lists_[size_t(b)].push_back({index, uint32_t(entries_++)});
  }
  stats_.triangle_entries += bins.size();
}

void Binner::add_clear(ClearRecord c, const SourceLoc& loc) {
  reserve(kBinClearRecordBytes, loc);
  c.seq = seq_++;
  c.offset = record_bytes_;
  if (mem_) mem_->record(record_bytes_, kBinClearRecordBytes, true);
  record_bytes_ += kBinClearRecordBytes;
  clears_.push_back(c);
}

void Binner::add_clear_color(uint8_t r, uint8_t g, uint8_t b, const SourceLoc& loc) {
  add_clear({0, BinClear{false, r, g, b, 0}, 0}, loc);
}

void Binner::add_clear_depth(uint32_t z, const SourceLoc& loc) { add_clear({0, BinClear{true, 0, 0, 0, z}, 0}, loc); }

void Binner::finish() { render_pass(true); }

void Binner::render_pass(bool final_pass) {
  for (int b = 0; b < nx_ * ny_; ++b) render_bin(b, final_pass);
  tris_.clear();
  tri_seq_.clear();
  tri_offset_.clear();
  clears_.clear();
  seq_ = 0;
  record_bytes_ = 0;
  entries_ = 0;
  for (auto& l : lists_) l.clear();
  used_ = 0;
}

// One bin's render pass: skipped when its list is empty and the pass has no clear,
// unless this is the last pass and the bin has never been stored (its colour, the
// image, must reach DRAM once). Triangles and clears in record order.
// Loads: what an earlier pass stored, or what bin.load_* asks for; stores: colour
// always (resolved, 4 bytes a pixel, on the last pass), depth on an overflow pass or
// with bin.store_depth.
void Binner::render_bin(int b, bool final_pass) {
  const auto& list = lists_[size_t(b)];
  if (list.empty() && clears_.empty() && !(final_pass && !color_stored_[size_t(b)])) return;
  const PixelRect r = bin_rect(b);
  const BinBytes loads = load_bytes(r, color_stored_[size_t(b)] || st_.bin.load_color,
                                    depth_stored_[size_t(b)] || st_.bin.load_depth);
  if (hooks_.begin_bin) hooks_.begin_bin(b, r, loads);
  load_bin(r, loads);
  ++stats_.bins_rendered;
  size_t c = 0;
  const auto clears_before = [&](uint32_t seq) {
    for (; c < clears_.size() && clears_[c].seq < seq; ++c) {
      stats_.geometry_bytes_read += kBinClearRecordBytes;
      if (mem_) mem_->record(clears_[c].offset, kBinClearRecordBytes, false);
      if (hooks_.clear) hooks_.clear(clears_[c].clear, r);
      else clear_bin_rect(fb_, r, clears_[c].clear);
    }
  };
  for (const Entry& e : list) {
    clears_before(tri_seq_[e.tri]);
    stats_.geometry_bytes_read += kBinListEntryBytes + kBinPrimitiveRecordBytes;
    if (mem_) {  // the entry, then the record it names
      mem_->entry(e.number, false);
      mem_->record(tri_offset_[e.tri], kBinPrimitiveRecordBytes, false);
    }
    const SetupTriangle& tri = tris_[e.tri];
    SetupTriangle walk = tri;
    walk.bbox = tri.bbox.intersect(r);
    if (!walk.bbox.empty()) draw_(tri, walk);
  }
  clears_before(seq_);
  const bool depth = !final_pass || st_.bin.store_depth;
  const BinBytes stores = store_bytes(r, final_pass, depth);
  store_bin(r, final_pass, stores);
  if (hooks_.end_bin) hooks_.end_bin(b, r, final_pass, stores);
  color_stored_[size_t(b)] = 1;
  if (depth) depth_stored_[size_t(b)] = 1;
}

// A bin's loads before its pass: colour and depth, every sample (4 and 2-or-4 bytes).
BinBytes Binner::load_bytes(const PixelRect& r, bool color, bool depth) const {
  const uint64_t samples = uint64_t(r.area()) * uint64_t(st_.samples);
  return {color ? samples * 4 : 0, depth ? samples * bin_depth_sample_bytes(st_.depth_bits) : 0};
}

// A bin's stores after its pass: colour always, resolved (4 bytes a pixel) on the last
// pass, every sample on an overflow pass; depth when `depth`.
BinBytes Binner::store_bytes(const PixelRect& r, bool final_pass, bool depth) const {
  const uint64_t samples = uint64_t(r.area()) * uint64_t(st_.samples);
  return {final_pass ? uint64_t(r.area()) * 4 : samples * 4,
          depth ? samples * bin_depth_sample_bytes(st_.depth_bits) : 0};
}

void Binner::load_bin(const PixelRect& r, BinBytes bytes) {
  stats_.framebuffer_bytes_read += bytes.total();
  if (!mem_) return;
  if (bytes.color) mem_->color(r, false);
  if (bytes.depth) mem_->depth(r, false);
}

void Binner::store_bin(const PixelRect& r, bool final_pass, BinBytes bytes) {
  stats_.framebuffer_bytes_written += bytes.total();
  if (!mem_) return;
  if (final_pass && st_.samples > 1) mem_->resolved_color(r);
  else mem_->color(r, true);
  if (bytes.depth) mem_->depth(r, true);
}

void clear_bin_rect(Framebuffer& fb, const PixelRect& r, const BinClear& c) {
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      for (int s = 0; s < fb.samples; ++s) {
        if (c.depth) {
          fb.set_depth(x, y, s, c.z);
          continue;
        }
        uint8_t* p = fb.sample(x, y, s);
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        p[3] = 255;
      }
}

void check_binned_command(const Command& cmd, const RasterState& st) {
  const auto refuse = [&](const std::string& what) {
    throw SceneError(cmd.loc.str() + ": " + what + " and pipeline.mode = binned: the binned pipeline does not draw "
                     "it yet; use pipeline.mode = immediate (docs/binning.md)");
  };
  if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body)) refuse(std::string("'") + d2->keyword + "' (2D drawing)");
  if (const auto* p = std::get_if<CmdPrimitives>(&cmd.body)) {
    if (p->texture.enabled()) refuse("drawn with texture '" + p->texture.image->name + "' bound");
    if (draws_homogeneous(*p, st)) refuse("clip.method = homogeneous");
  }
}

}  // namespace rastsim
