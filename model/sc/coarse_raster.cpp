// SPDX-License-Identifier: Apache-2.0
#include "sc/coarse_raster.h"

#include <algorithm>

#include "ref/rop.h"

namespace rastsim::sc {

void CoarseRaster::body() {
  ctx_.render.traversal_method = tp_.method;
  for (;;) {
    const SetupItem in = read(in_);
    if (in.state && hiz_) hiz_->state(*in.state);
    if (in.state && binned_) bin_clip_ = bin_walk_clip(*in.state, bin_clip_);
    if (in.state && interlock_) interlock_->sent_state();
    if (pass_state(in, out_)) continue;
    switch (tp_.method) {
      case Traversal::Tiled: walk_tiled(in); break;
      case Traversal::Bbox: {
        TraversalCounters& c = ctx_.render.traversal;
        ++c.tiles_visited;
        ++c.tiles_partial;
        const PixelRect box = walk_box(*in.work);
        attribute_to(box.x0, box.y0);
        busy(p_.coarse_walk_cycles(1));
        write(out_, TileItem{nullptr, TileWork{in.work, box, TileClass::Partial}});
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
  const PixelRect box = walk_box(t);
  attribute_to(box.x0, box.y0);  // no leaf: the walk's cycles go to its first tile
  rastsim::walk_hierarchical(t, box, tp_.hier_levels, 0, frac_bits_, c, [&](const PixelRect& fp, TileClass cls) {
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
    const PixelRect box = walk_box(t);
    const PixelRect tiles = tile_range(box, tile_size_);
    uint64_t cycles_done = 0;  // cycles of this walk spent
    // One tile a cycle at most, from windows of coarse.tiles_per_cycle (as the RTL).
    TiledWalk walk = p_.tiled_walk();
    attribute_to(box.x0, box.y0);
    for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
      for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
        const PixelRect fp = tile_footprint(box, tile_size_, tx, ty);
        ++c.tiles_visited;
        const TileClass cls = classify_tile(t, fp, frac_bits_);
        if (cls != TileClass::Rejected && interlock_) hiz_interlock_wait(walk, fp, cycles_done);
        // The tile's entry reads at its test's cycle (timing/hiz_memory_port.h).
        if (mem_) mem_->begin(now() + walk.next_window() - 1 - cycles_done);
        const HizDecision hiz = cls != TileClass::Rejected && hiz_ ? hiz_->test(t, fp, cls) : HizDecision::Draw;
        const bool culled = hiz == HizDecision::Culled;
        hiz_stall();  // the test's entries
        const uint64_t leave_at = walk.visit(cls != TileClass::Rejected && !culled);
        if (cls == TileClass::Rejected) {
          ++c.tiles_rejected;
          continue;
        }
        ++(cls == TileClass::Accepted ? c.tiles_accepted : c.tiles_partial);
        if (culled) continue;  // counted by its class, as the reference's walk does
        std::shared_ptr<std::vector<HizSpillWrite>> writes;
        if (flush_) {  // the flush: the ROP hands it to the engine (sc/hiz_flush.h)
          writes = std::make_shared<std::vector<HizSpillWrite>>();
          mem_->defer(true);
          hiz_->apply(t, fp, cls, writes.get());
          mem_->defer(false);
          if (writes->empty()) writes.reset();
        } else if (hiz_) {
          hiz_->apply(t, fp, cls);
        }
        attribute_to(fp.x0, fp.y0);  // the walk up to this tile, rejected tiles included
        busy(leave_at - cycles_done);
        cycles_done = leave_at;
        if (interlock_) interlock_->sent(fp);
        write(out_, TileItem{nullptr, TileWork{in.work, fp, cls, false, hiz == HizDecision::Accepted, std::move(writes)}});
      }
    }
    // The rest of the walk (rejected tiles after the last written one): the last tile's.
    if (!tiles.empty()) {
      const PixelRect last = tile_footprint(box, tile_size_, tiles.x1 - 1, tiles.y1 - 1);
      attribute_to(last.x0, last.y0);
    }
    busy(walk.cycles() - cycles_done);
  }
}

// Hi-Z's interlock: the tile's test in walk cycle w is at cycle now() + w - 1 - done (the
// walk's cycles since its last sent tile not yet charged); when a tile sent earlier on its
// blocks ends later (cycle e), the walk holds the tile and its window starts at it in
// cycle e: walk cycle e - now() + 1 + done (docs/depth-culling.md "The interlock"). A
// test that reads spilled entries also waits for the flush engine to be idle (rast_hiz_spill's
// busy_o, sc/hiz_flush.h).
void CoarseRaster::hiz_interlock_wait(TiledWalk& walk, const PixelRect& fp, uint64_t done) {
  const uint64_t test_at = now() + walk.next_window() - 1 - done;
  uint64_t free = interlock_->free_at(fp, now());
  if (flush_ && hiz_->table.spills(fp)) free = flush_->idle_from(std::max(free, test_at));
  if (free > test_at) walk.restart(free - now() + 1 + done);
}

// The walk waits for the step's spilled entries: busy the stall; the next step starts
// then (timing/hiz_memory_port.h).
void CoarseRaster::hiz_stall() {
  if (!mem_) return;
  if (const uint64_t stall = mem_->wait()) busy(stall);
  mem_->begin(now());
}

}  // namespace rastsim::sc
