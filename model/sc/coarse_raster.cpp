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
    if (in.state && interlock_) {
      const uint64_t entry = interlock_->sent_state();
      if (lag_)
        if (const auto z = hiz_->depth_clear(*in.state)) lag_pending_.push_back({entry, {}, z});
    }
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
        // depth.hiz_sync = lagged: the test is against the lagged table, the walk held only
        // for a state item in flight; else the interlock's hold (and the flush engine's).
        const bool lagged = lag_ && cls != TileClass::Rejected;
        if (cls != TileClass::Rejected && interlock_) {
          if (lagged) lag_state_wait(walk, cycles_done);
          else hiz_interlock_wait(walk, fp, cycles_done);
        }
        // The tile's entry reads at its test's cycle (timing/hiz_memory_port.h).
        if (mem_) mem_->begin(now() + walk.next_window() - 1 - cycles_done);
        HizDecision hiz = HizDecision::Draw;
        if (lagged) hiz = hiz_lagged(t, walk, fp, cls, cycles_done);
        else if (cls != TileClass::Rejected && hiz_) hiz = hiz_->test(t, fp, cls);
        if (hiz != HizDecision::Draw && ctx_.on_hiz) ctx_.on_hiz(t, fp, hiz);
        const bool culled = hiz == HizDecision::Culled;
        hiz_stall();  // the test's entries
        const uint64_t leave_at = walk.visit(cls != TileClass::Rejected && !culled);
        if (cls == TileClass::Rejected) {
          ++c.tiles_rejected;
          continue;
        }
        ++(cls == TileClass::Accepted ? c.tiles_accepted : c.tiles_partial);
        if (culled) continue;  // counted by its class, as the reference's walk does
        std::vector<HizWrite> writes;  // for the lagged table
        std::shared_ptr<std::vector<HizSpillWrite>> spilled;
        if (flush_) {  // the flush: the ROP hands it to the engine (sc/hiz_flush.h)
          spilled = std::make_shared<std::vector<HizSpillWrite>>();
          mem_->defer(true);
          hiz_->apply(t, fp, cls, lag_ ? &writes : nullptr, spilled.get());
          mem_->defer(false);
          if (spilled->empty()) spilled.reset();
        } else if (hiz_) {
          hiz_->apply(t, fp, cls, lag_ ? &writes : nullptr);
        }
        attribute_to(fp.x0, fp.y0);  // the walk up to this tile, rejected tiles included
        busy(leave_at - cycles_done);
        cycles_done = leave_at;
        if (interlock_) {
          const uint64_t entry = interlock_->sent(fp);
          if (!writes.empty()) lag_pending_.push_back({entry, std::move(writes), std::nullopt});
        }
        write(out_, TileItem{nullptr, TileWork{in.work, fp, cls, false, hiz == HizDecision::Accepted, std::move(spilled)}});
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

// depth.hiz_sync = lagged (docs/depth-culling.md "Lagged"): the tile is tested in walk
// cycle w at t_test = now() + w - 1 - done, as under the interlock, but not held for its
// blocks: against the table as the ROP has written it by t_test (every update whose
// entry ended by then), accepted only when no entry in flight at t_test touches its
// blocks. A state item in flight (a depth clear) holds it to the item's end
// (lag_state_wait, before the test's entry reads begin). Its spilled entries are read
// without waiting for the flush engine: memory holds what the ROP has written back.
void CoarseRaster::lag_state_wait(TiledWalk& walk, uint64_t done) {
  const uint64_t test_at = now() + walk.next_window() - 1 - done;
  const uint64_t state_free = interlock_->state_free_at();
  if (state_free > test_at) walk.restart(state_free - now() + 1 + done);
}

HizDecision CoarseRaster::hiz_lagged(const SetupTriangle& t, TiledWalk& walk, const PixelRect& fp, TileClass cls,
                                     uint64_t done) {
  const uint64_t test_at = now() + walk.next_window() - 1 - done;
  const bool idle = !interlock_->busy_at(fp, now(), test_at);
  lag_absorb(test_at);
  return hiz_->test_lagged(t, fp, cls, *lag_, idle || ctx_.hiz_lag_accept_busy);
}

// The lagged table takes the updates whose entries ended by cycle `at`, in send order
// (the ROP ends its entries in that order, so the first not ended stops the rest).
void CoarseRaster::lag_absorb(uint64_t at) {
  while (!lag_pending_.empty() && interlock_->ended_by(lag_pending_.front().entry, at)) {
    const LagUpdate& u = lag_pending_.front();
    if (u.clear) lag_->clear(*u.clear);
    for (const HizWrite& w : u.writes) lag_->write(w.x, w.y, w.z);
    lag_->flush();
    lag_pending_.pop_front();
  }
}

// The walk waits for the step's spilled entries: busy the stall; the next step starts
// then (timing/hiz_memory_port.h).
void CoarseRaster::hiz_stall() {
  if (!mem_) return;
  if (const uint64_t stall = mem_->wait()) busy(stall);
  mem_->begin(now());
}

}  // namespace rastsim::sc
