// SPDX-License-Identifier: Apache-2.0
#include "sc/coarse_raster.h"

#include <algorithm>

#include "ref/rop.h"

namespace rastsim::sc {

void CoarseRaster::body() {
  ctx_.render.traversal_method = tp_.method;
  for (;;) {
    const SetupItem in = read(in_);
    if (in.state && hiz_) hiz_state(*in.state);
    if (pass_state(in, out_)) continue;
    switch (tp_.method) {
      case Traversal::Tiled: walk_tiled(in); break;
      case Traversal::Bbox: {
        TraversalCounters& c = ctx_.render.traversal;
        ++c.tiles_visited;
        ++c.tiles_partial;
        attribute_to(in.work->bbox.x0, in.work->bbox.y0);
        busy(p_.coarse_walk_cycles(1));
        write(out_, TileItem{nullptr, TileWork{in.work, in.work->bbox, TileClass::Partial}});
        break;
      }
      case Traversal::Hierarchical: walk_hierarchical(in); break;
      case Traversal::Scanline: walk_scanline(in); break;
    }
  }
}

void CoarseRaster::walk_hierarchical(const SetupItem& in) {
  TraversalCounters& c = ctx_.render.traversal;
  const SetupTriangle& t = *in.work;
  const uint64_t visited0 = c.tiles_visited;
  uint64_t cycles_done = 0;
  attribute_to(t.bbox.x0, t.bbox.y0);  // no leaf: the walk's cycles go to its first tile
  rastsim::walk_hierarchical(t, t.bbox, tp_.hier_levels, 0, frac_bits_, c, [&](const PixelRect& fp, TileClass cls) {
    // This leaf was the (tiles_visited - visited0)-th tile classified, counted from 1.
    const uint64_t leave_at = (c.tiles_visited - visited0 - 1) / p_.coarse_tiles_per_cycle + 1;
    attribute_to(fp.x0, fp.y0);  // the walk up to this leaf, and the rest after the last
    busy(leave_at - cycles_done);
    cycles_done = leave_at;
    write(out_, TileItem{nullptr, TileWork{in.work, fp, cls}});
  });
  busy(p_.coarse_walk_cycles(c.tiles_visited - visited0) - cycles_done);
}

void CoarseRaster::walk_scanline(const SetupItem& in) {
  const SetupTriangle& t = *in.work;
  std::vector<std::pair<int, int>> pixels;
  attribute_to(t.bbox.x0, t.bbox.y0);  // the edge walker's setup
  busy(p_.scanline_walk_cycles(0));
  scanline_spans(t, tp_.scan_arith, frac_bits_, [&](int py, int x0, int x1) {
    attribute_to(x0 < x1 ? x0 : t.bbox.x0, py);  // the span's row (its first pixel's tile)
    busy(1);  // one row a cycle
    if (x0 >= x1) return;
    ++ctx_.render.traversal.spans;
    for (int px = x0; px < x1; ++px) pixels.emplace_back(px, py);
    write(out_, TileItem{nullptr, TileWork{in.work, PixelRect{x0, py, x1, py + 1}, TileClass::Accepted, true}});
  });
  check_->add_triangle(t, frac_bits_, pixels, ctx_.render.coverage);
}

void CoarseRaster::walk_tiled(const SetupItem& in) {
  TraversalCounters& c = ctx_.render.traversal;
  {
    const SetupTriangle& t = *in.work;
    const PixelRect tiles = tile_range(t.bbox, tile_size_);
    uint64_t cycles_done = 0;  // cycles of this walk spent
    // One tile a cycle at most, from windows of coarse.tiles_per_cycle (as the RTL).
    TiledWalk walk = p_.tiled_walk();
    attribute_to(t.bbox.x0, t.bbox.y0);
    for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
      for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
        const PixelRect fp = tile_footprint(t.bbox, tile_size_, tx, ty);
        ++c.tiles_visited;
        const TileClass cls = classify_tile(t, fp, frac_bits_);
        const HizDecision hiz = cls != TileClass::Rejected && hiz_ ? hiz_test(t, fp, cls) : HizDecision::Draw;
        const bool culled = hiz == HizDecision::Culled;
        const uint64_t leave_at = walk.visit(cls != TileClass::Rejected && !culled);
        if (cls == TileClass::Rejected) {
          ++c.tiles_rejected;
          continue;
        }
        ++(cls == TileClass::Accepted ? c.tiles_accepted : c.tiles_partial);
        if (culled) continue;  // counted by its class, as the reference's walk does
        if (hiz_) hiz_apply(t, fp, cls);
        attribute_to(fp.x0, fp.y0);  // the walk up to this tile, rejected tiles included
        busy(leave_at - cycles_done);
        cycles_done = leave_at;
        write(out_, TileItem{nullptr, TileWork{in.work, fp, cls, false, hiz == HizDecision::Accepted}});
      }
    }
    // The rest of the walk (rejected tiles after the last written one): the last tile's.
    if (!tiles.empty()) {
      const PixelRect last = tile_footprint(t.bbox, tile_size_, tiles.x1 - 1, tiles.y1 - 1);
      attribute_to(last.x0, last.y0);
    }
    busy(walk.cycles() - cycles_done);
  }
}

CoarseRaster::HizShadow::HizShadow(const RasterState& a)
    : depth(a.fb_width, a.fb_height, 1),
      table(a.hiz_mode, a.hiz_block, a.hiz_bytes, a.fb_width, a.fb_height, a.depth_bits) {
  depth.clear_depth(static_cast<uint32_t>((uint64_t{1} << a.depth_bits) - 1));  // as the ROP's
}

// The reference's test (pipeline.cpp HizFilter): a culled tile's covered pixels counted.
HizDecision CoarseRaster::hiz_test(const SetupTriangle& t, const PixelRect& fp, TileClass cls) {
  const HizDecision d = hiz_->table.test(fp, tile_depth_range(t, fp, frac_bits_), arch_.depth_func);
  if (d == HizDecision::Culled) {
    uint64_t n = 0;
    if (cls == TileClass::Accepted) n = uint64_t(fp.area());
    else fine_raster_partial(t, fp, frac_bits_, [&](int, int, uint32_t) { ++n; });
    hiz_->table.stats.fragments_culled += n;
  }
  return d;
}

// The depth writes the ROP will make for this tile, applied to the shadow and the table
// now, then the tile's blocks flushed (the reference's order: walk order, one sample).
void CoarseRaster::hiz_apply(const SetupTriangle& t, const PixelRect& fp, TileClass cls) {
  HizShadow& h = *hiz_;
  const auto pixel = [&](int px, int py, uint32_t) {
    const uint32_t z = interpolate_plane(t, px, py, frac_bits_).z;
    if (!depth_test(arch_.depth_func, z, std::as_const(h.depth).depth_at(px, py, 0)) || !arch_.depth_write) return;
    h.depth.set_depth(px, py, 0, z);
    h.table.write(px, py, z);
  };
  if (cls == TileClass::Accepted) fine_raster_accepted(fp, pixel);
  else fine_raster_partial(t, fp, frac_bits_, pixel);
  h.table.flush();
}

void CoarseRaster::hiz_state(const Command& cmd) {
  const auto* c = std::get_if<CmdClearDepth>(&cmd.body);
  if (!c) return;
  if (const auto z = quantize_unorm(c->z, arch_.depth_bits)) {  // a bad value is the ROP's error to report
    hiz_->depth.clear_depth(*z);
    hiz_->table.clear(*z);
  }
}

}  // namespace rastsim::sc
