// SPDX-License-Identifier: Apache-2.0
#include "ref/hiz.h"

#include <algorithm>
#include <bit>
#include <utility>

#include "ref/fine_raster.h"
#include "ref/fixed_point.h"
#include "ref/hiz_entry.h"
#include "ref/interpolate.h"
#include "ref/rop.h"

namespace rastsim {

DepthRange tile_depth_range(const SetupTriangle& t, const PixelRect& fp, int frac_bits) {
  // The footprint's corner pixel centres (raw units): num is linear, so its extremes over
  // the centres lie among these four.
  const int64_t xs[2] = {t.sample_x(fp.x0, frac_bits), t.sample_x(fp.x1 - 1, frac_bits)};
  const int64_t ys[2] = {t.sample_y(fp.y0, frac_bits), t.sample_y(fp.y1 - 1, frac_bits)};
  i128 num_min = 0, num_max = 0;
  bool first = true;
  for (int64_t sx : xs)
    for (int64_t sy : ys) {
      // Weight of vertex k is the edge opposite it (interpolate.cpp): w = E1, E2, E0.
      const i128 num = t.edge[1].eval(sx, sy) * t.z[0] + t.edge[2].eval(sx, sy) * t.z[1] +
                       t.edge[0].eval(sx, sy) * t.z[2];
      num_min = first ? num : std::min(num_min, num);
      num_max = first ? num : std::max(num_max, num);
      first = false;
    }
  const i128 lo = div_round_in<i128>(num_min, t.area2, Rounding::Floor);                 // floor
  const i128 hi = -div_round_in<i128>(-num_max, t.area2, Rounding::Floor);               // ceil
  const uint32_t zmin = std::min({t.z[0], t.z[1], t.z[2]}), zmax = std::max({t.z[0], t.z[1], t.z[2]});
  // Clamped to [-1, 2^D] (DepthRange): lo >= 0 and hi <= 2^D - 1 already (the vertex
  // clamp); a corner plane beyond the depth range keeps its side of every stored bound.
  const i128 top = i128(1) << t.depth_bits;
  return {static_cast<int64_t>(std::min<i128>(std::max<i128>(zmin, lo), top)),
          static_cast<int64_t>(std::max<i128>(std::min<i128>(zmax, hi), -1))};
}

HizStats& HizStats::operator+=(const HizStats& o) {
  for (auto m : {&HizStats::tiles_tested, &HizStats::tiles_culled, &HizStats::tiles_accepted,
                 &HizStats::fragments_culled, &HizStats::block_updates, &HizStats::layer_completions,
                 &HizStats::dram_reads, &HizStats::dram_writes, &HizStats::bytes_read, &HizStats::bytes_written})
    this->*m += o.*m;
  return *this;
}

HizTable::HizTable(HizMode mode, int block, int64_t onchip_bytes, int width, int height, int depth_bits)
    : mode_(mode), B_(block), log2B_(std::countr_zero(unsigned(block))), nx_((width + block - 1) / block),
      ny_((height + block - 1) / block), width_(width), height_(height), depth_bits_(depth_bits),
      entry_bytes_(hiz_entry_bytes(mode, block, depth_bits)),
      onchip_(hiz_onchip_blocks(mode, block, onchip_bytes, width, height, depth_bits)),
      blocks_(size_t(nx_) * size_t(ny_)) {
  stats.enabled = true;
  clear(static_cast<uint32_t>((uint64_t{1} << depth_bits) - 1));
}

int HizTable::full_count(int bx, int by) const {
  return (std::min(width_, (bx + 1) * B_) - bx * B_) * (std::min(height_, (by + 1) * B_) - by * B_);
}

void HizTable::clear(uint32_t z) {
  for (Block& b : blocks_) b = Block{z, z, ~0u, 0, {}, 0, false};  // exact bounds, the empty layer
  dirty_.clear();
}

DepthRange HizTable::bounds(const PixelRect& fp) const {
  DepthRange r{int64_t{~0u}, 0};
  for (int by = fp.y0 >> log2B_; by <= (fp.y1 - 1) >> log2B_; ++by)
    for (int bx = fp.x0 >> log2B_; bx <= (fp.x1 - 1) >> log2B_; ++bx) {
      const Block& b = blocks_[size_t(index(bx, by))];
      r.lo = std::min<int64_t>(r.lo, b.zmin);
      r.hi = std::max<int64_t>(r.hi, b.zmax);
    }
  return r;
}

HizDecision HizTable::test(const PixelRect& fp, DepthRange z, DepthFunc func, bool may_accept) {
  const bool minmax = mode_ == HizMode::MinMax;
  const bool handled = func == DepthFunc::Less || func == DepthFunc::LEqual ||
                       (minmax && (func == DepthFunc::Greater || func == DepthFunc::GEqual));
  if (!handled || fp.empty()) return HizDecision::Draw;
  ++stats.tiles_tested;
  read_spilled(fp);
  const DepthRange b = bounds(fp);  // b.lo: nearest stored (minmax only), b.hi: farthest
  bool cull = false, accept = false;
  switch (func) {
    case DepthFunc::Less: cull = z.lo >= b.hi, accept = minmax && z.hi < b.lo; break;
    case DepthFunc::LEqual: cull = z.lo > b.hi, accept = minmax && z.hi <= b.lo; break;
    case DepthFunc::Greater: cull = z.hi <= b.lo, accept = z.lo > b.hi; break;
    case DepthFunc::GEqual: cull = z.hi < b.lo, accept = z.lo >= b.hi; break;
    default: break;
  }
  if (cull) {
    ++stats.tiles_culled;
    return HizDecision::Culled;
  }
  if (accept && may_accept) {
    ++stats.tiles_accepted;
    return HizDecision::Accepted;
  }
  return HizDecision::Draw;
}

void HizTable::read_spilled(const PixelRect& fp) {
  for (int by = fp.y0 >> log2B_; by <= (fp.y1 - 1) >> log2B_; ++by)
    for (int bx = fp.x0 >> log2B_; bx <= (fp.x1 - 1) >> log2B_; ++bx)
      if (spilled(index(bx, by))) spilled_access(index(bx, by), false);
}

void HizTable::write(int x, int y, uint32_t z) {
  const int bx = x >> log2B_, by = y >> log2B_, i = index(bx, by);
  Block& b = blocks_[size_t(i)];
  b.zmax = std::max(b.zmax, z);
  b.zmin = std::min(b.zmin, z);
  b.lmax = std::max(b.lmax, z);
  b.lmin = std::min(b.lmin, z);
  const int bit = ((y - by * B_) << log2B_) + (x - bx * B_);
  uint64_t& w = b.mask[size_t(bit >> 6)];
  const uint64_t m = uint64_t{1} << (bit & 63);
  if (!(w & m)) {
    w |= m;
    if (++b.written == full_count(bx, by)) {  // every pixel written during the layer
      b.zmax = std::min(b.zmax, b.lmax);
      b.zmin = std::max(b.zmin, b.lmin);
      b.mask = {};
      b.written = 0;
      b.lmin = ~0u;
      b.lmax = 0;
      ++stats.layer_completions;
    }
  }
  if (!b.dirty) {
    b.dirty = true;
    dirty_.push_back(i);
  }
}

void HizTable::flush() {
  for (int i : dirty_) {
    blocks_[size_t(i)].dirty = false;
    ++stats.block_updates;
    if (!spilled(i)) continue;
    spilled_access(i, false);  // the read-modify-write of the entry
    spilled_access(i, true);
  }
  dirty_.clear();
}

void HizTable::spilled_access(int i, bool write) {
  ++(write ? stats.dram_writes : stats.dram_reads);
  (write ? stats.bytes_written : stats.bytes_read) += uint64_t(entry_bytes_);
  if (on_access) on_access(dram_base + uint64_t(i - onchip_) * uint64_t(entry_bytes_), uint64_t(entry_bytes_), write);
}

HizTracker::HizTracker(const RasterState& st)
    : table(st.hiz_mode, st.hiz_block, st.hiz_bytes, st.fb_width, st.fb_height, st.depth_bits), st_(st),
      depth_(st.fb_width, st.fb_height, 1) {
  table.dram_base = st.hiz_base;
  depth_.clear_depth(static_cast<uint32_t>((uint64_t{1} << st.depth_bits) - 1));  // as the ROP's
}

void HizTracker::count_culled(const SetupTriangle& t, const PixelRect& fp, TileClass cls) {
  uint64_t n = 0;
  if (cls == TileClass::Accepted) n = uint64_t(fp.area());
  else fine_raster_partial(t, fp, st_.coord_format.frac_bits, [&](int, int, uint32_t) { ++n; });
  table.stats.fragments_culled += n;
}

// The reference's test (pipeline.cpp HizFilter): a culled tile's covered pixels counted.
HizDecision HizTracker::test(const SetupTriangle& t, const PixelRect& fp, TileClass cls) {
  const HizDecision d = table.test(fp, tile_depth_range(t, fp, st_.coord_format.frac_bits), st_.depth_func);
  if (d == HizDecision::Culled) count_culled(t, fp, cls);
  return d;
}

HizDecision HizTracker::test_lagged(const SetupTriangle& t, const PixelRect& fp, TileClass cls, HizTable& stale,
                                    bool idle) {
  if (!fp.empty()) table.read_spilled(fp);  // the entries test() reads (a tracker's function is handled)
  const HizDecision d = stale.test(fp, tile_depth_range(t, fp, st_.coord_format.frac_bits), st_.depth_func, idle);
  if (d == HizDecision::Culled) count_culled(t, fp, cls);
  return d;
}

// The depth writes the ROP will make for this tile, applied to the copy and the table
// now, then the tile's blocks flushed (the reference's order: walk order, one sample).
void HizTracker::apply(const SetupTriangle& t, const PixelRect& fp, TileClass cls, std::vector<HizWrite>* writes,
                       std::vector<HizSpillWrite>* spilled) {
  const int F = st_.coord_format.frac_bits;
  const int log2b = std::countr_zero(unsigned(st_.hiz_block)), nx = (st_.fb_width + st_.hiz_block - 1) / st_.hiz_block;
  uint32_t k = 0;  // the covered pixel's index in the tile (the ROP's fragment order)
  const auto pixel = [&](int px, int py, uint32_t) {
    const uint32_t z = interpolate_plane(t, px, py, F).z;
    const uint32_t frag = k++;
    if (!depth_test(st_.depth_func, z, std::as_const(depth_).depth_at(px, py, 0)) || !st_.depth_write) return;
    depth_.set_depth(px, py, 0, z);
    table.write(px, py, z);
    if (writes) writes->push_back({px, py, z});
    const int block = (py >> log2b) * nx + (px >> log2b);
    if (spilled && table.spilled(block)) spilled->push_back({frag, block});
  };
  if (cls == TileClass::Accepted) fine_raster_accepted(fp, pixel);
  else fine_raster_partial(t, fp, F, pixel);
  table.flush();
}

std::optional<uint32_t> HizTracker::depth_clear(const Command& cmd) const {
  const auto* c = std::get_if<CmdClearDepth>(&cmd.body);
  if (!c) return std::nullopt;
  return quantize_unorm(c->z, st_.depth_bits);  // a bad value is the ROP's error to report
}

void HizTracker::state(const Command& cmd) {
  if (const auto z = depth_clear(cmd)) {
    depth_.clear_depth(*z);
    table.clear(*z);
  }
}

bool hiz_applies(const RasterState& st) {
  if (st.hiz_mode == HizMode::Off || st.samples != 1 || st.traversal != Traversal::Tiled ||
      st.interp_method != InterpMethod::Plane)
    return false;
  switch (st.depth_func) {
    case DepthFunc::Less:
    case DepthFunc::LEqual: return true;
    case DepthFunc::Greater:
    case DepthFunc::GEqual: return st.hiz_mode == HizMode::MinMax;
    default: return false;
  }
}

}  // namespace rastsim
