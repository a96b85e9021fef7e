// SPDX-License-Identifier: Apache-2.0
// Coarse raster: the tile walk of one set-up triangle with early-out and early-in
// (ref/coarse_raster.h: tile_range, tile_footprint, classify_tile).
//
// - Visits every tile overlapping the triangle's clipped bounding box, row by row: each
//   cycle classifies a window of coarse.tiles_per_cycle tiles and sends at most one,
//   the window's first surviving tile, the next window starting after it
//   (timing/tiled_walk.h, as rtl/rast_coarse_raster.sv): at least
//   max(1, ceil(V / tiles_per_cycle)) cycles for V tiles, and one a surviving tile.
// - Rejected tiles go no further; an accepted or partial tile is written to the tile
//   FIFO at the end of the cycle that sent it.
// - Counts tiles_visited / rejected / accepted / partial.
// - Hi-Z (depth.hiz where hiz_applies, docs/depth-culling.md): an accepted or partial
//   tile is tested against the bound table with its corner depth range (ref/hiz.h); a
//   culled tile costs its window slot as a rejected one and goes no further. The table is
//   functional-first: this stage keeps the depth buffer and table the reference would
//   have at this tile (each surviving tile's fragments' depths applied here, in walk
//   order, as the ROP will), a zero-lag Hi-Z, so its decisions and counts equal the
//   reference's and its cycles are those of an ideally synchronised table. With
//   memory.model = "dram" a test's spilled entries' reads stall the walk until they arrive
//   (busy the stall too), and a test that reads spilled entries waits for the flush
//   engine to be idle; a drawn tile's flush is timed by the ROP as rast_hiz_spill's
//   engine makes it (sc/hiz_flush.h).
//   The interlock (sc/hiz_interlock.h, as rast_top's): a tile is tested only once every
//   earlier tile on its blocks has left the ROP; until then the walk holds it, and its
//   window restarts at it in the cycle the last of them ends (TiledWalk::restart).
//   depth.hiz_sync = lagged: no hold; a tile is tested against lag_, the table as the
//   ROP has written it by the test's cycle (each sent tile's depth writes applied at its
//   ROP end, a depth clear at its), accepted only when no tile in flight touches its
//   blocks (HizTracker::test_lagged); the walk holds only while a state item is in
//   flight. Spilled entries: read (and their reads waited for) as with the interlock.
// The other raster.traversal methods (docs/traversal.md), same functions as the
// reference (ref/traverse.h):
// - bbox: one partial "tile", the whole clipped bbox, in 1 cycle.
// - hierarchical: walk_hierarchical at coarse.tiles_per_cycle tiles a cycle over every
//   level's tiles (the tiled equation with V = the tiles of all levels); the leaves
//   (accepted tiles of any level, partial tiles of the last) go to the tile FIFO.
// - scanline: the edge walker. coarse.scanline_setup_cycles, then one row a cycle; each
//   non-empty span leaves as one tile item (a one-row footprint marked `span`) at the
//   end of its row's cycle. The spans are checked against the exact coverage here
//   (ref/study/coverage_check.h), where the whole triangle's pixels are known.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "ref/framebuffer.h"
#include "ref/hiz.h"
#include "ref/study/coverage_check.h"
#include "ref/traverse.h"
#include "sc/binning.h"
#include "sc/hiz_flush.h"
#include "sc/hiz_interlock.h"
#include "sc/tri_setup.h"
#include "timing/hiz_memory_port.h"

namespace rastsim::sc {

struct TileWork {
  LocalPtr<const SetupTriangle> tri;
  PixelRect footprint;  // the tile clipped to the triangle's bounding box
  TileClass cls = TileClass::Partial;  // Accepted or Partial
  bool span = false;  // scanline: a span (one row, every pixel covered, no tests)
  bool hiz_accepted = false;  // Hi-Z accepted it (minmax): every fragment passes, the ROP reads no depth
  // Its depth writes to spilled Hi-Z blocks (memory.model = dram), for the ROP to time
  // their flush (timing/hiz_memory_port.h); null when none.
  std::shared_ptr<const std::vector<HizSpillWrite>> hiz_writes;
};
using TileItem = Item<TileWork>;

class CoarseRaster : public Stage {
 public:
  static constexpr StageId kId = StageId::CoarseRaster;
  CoarseRaster(SimContext& ctx, const RasterState& arch, const TimingParams& p,
               Link<SetupItem>& in, Link<TileItem>& out,
             sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), tile_size_(arch.tile_size), frac_bits_(arch.coord_format.frac_bits),
        tp_(traversal_params(arch)), p_(p), in_(in), out_(out), arch_(arch),
        binned_(arch.bin.mode == PipelineMode::Binned) {
    if (!traversal_is_exact(tp_.method)) check_.emplace(arch.fb_width, arch.fb_height);
    ctx_.render.hiz_mode = arch.hiz_mode;
    if (hiz_applies(arch)) hiz_.emplace(arch);
    // The interlock (sc/hiz_interlock.h) times the tests as rast_top's; fine raster and the
    // ROP record their ends through ctx. Not in the binned pipeline (its bins reorder the
    // ROP's work).
    if (hiz_ && !binned_) {
      interlock_ = std::make_unique<HizInterlock>(arch.hiz_block, ctx_);
      ctx_.hiz_interlock = interlock_.get();
      if (arch.hiz_sync == HizSync::Lagged)
        lag_ = std::make_unique<HizTable>(arch.hiz_mode, arch.hiz_block, arch.hiz_bytes, arch.fb_width, arch.fb_height,
                                          arch.depth_bits);
    }
  }
  // memory.model = "dram" (before the run): the spilled Hi-Z table's entries become
  // requests through `mem` (the hiz client, timing/hiz_memory_port.h), which must outlive
  // the run. Nothing without a table.
  void attach_memory(MemorySystem& mem) {
    if (!hiz_) return;
    mem_ = std::make_unique<HizMemoryPort>(mem);
    mem_->attach(hiz_->table);
    // The flush engine, where blocks spill and the ROP's order is the walk's (not binned):
    // its requests and the others' enter the DRAM in time order (sc/hiz_flush.h).
    if (hiz_->table.onchip_blocks() < hiz_->table.blocks() && interlock_) {
      flush_ = std::make_unique<HizFlush>("hiz_flush", ctx_, *mem_);
      ctx_.hiz_flush = flush_.get();
      ctx_.memory_time_order = ctx_.wake_writers_at_free_slot = true;
    }
  }
  const HizMemoryPort* memory_port() const { return mem_.get(); }
  // After the run: the Hi-Z flush engine's idle cycle (sc/hiz_flush.h), 0 without one.
  uint64_t hiz_flush_end() const { return flush_ ? flush_->end() : 0; }
  // The Hi-Z unit's counts into ctx.render.hiz (call once, after the simulation).
  void finish_hiz() {
    if (!hiz_) return;
    ctx_.render.hiz = hiz_->table.stats;
    if (!lag_) return;  // lagged: the tests against lag_ too (its writes' counts are table's)
    ctx_.render.hiz.tiles_tested += lag_->stats.tiles_tested;
    ctx_.render.hiz.tiles_culled += lag_->stats.tiles_culled;
    ctx_.render.hiz.tiles_accepted += lag_->stats.tiles_accepted;
  }
  // Counts cracks and overlaps of every triangle walked into ctx.render.coverage (call
  // once, after the simulation).
  void finish_coverage() {
    if (check_) check_->finish(ctx_.render.coverage);
  }

 private:
  void body() override;
  void walk_tiled(const SetupItem& in);
  void hiz_stall();
  void hiz_interlock_wait(TiledWalk& walk, const PixelRect& fp, uint64_t done);
  void lag_state_wait(TiledWalk& walk, uint64_t done);
  HizDecision hiz_lagged(const SetupTriangle& t, TiledWalk& walk, const PixelRect& fp, TileClass cls, uint64_t done);
  void lag_absorb(uint64_t at);
  void walk_hierarchical(const SetupItem& in);
  void walk_scanline(const SetupItem& in);
  int tile_size_, frac_bits_;
  TraversalParams tp_;
  std::optional<CoverageCheck> check_;
  const TimingParams& p_;
  Link<SetupItem>& in_;
  Link<TileItem>& out_;
  RasterState arch_;  // the depth state and the table's parameters
  std::optional<HizTracker> hiz_;  // functional-first Hi-Z (ref/hiz.h)
  std::unique_ptr<HizMemoryPort> mem_;  // memory.model = "dram" with a table, else null
  std::unique_ptr<HizInterlock> interlock_;  // with a table (immediate mode), else null
  // depth.hiz_sync = lagged (with the interlock's record of what is in flight): the table
  // as the ROP has written it, and the updates sent but not yet in it, in send order
  // (a drawn tile's depth writes or a depth clear; its interlock entry gives its end).
  struct LagUpdate {
    uint64_t entry = 0;
    std::vector<HizWrite> writes;
    std::optional<uint32_t> clear;
  };
  std::unique_ptr<HizTable> lag_;
  std::deque<LagUpdate> lag_pending_;
  std::unique_ptr<HizFlush> flush_;  // with spilled blocks and a memory (attach_memory), else null
  // pipeline.mode = binned (sc/binning.h): each triangle's box clipped to the bin of the
  // last begin marker (the reference's draw(tri, walk)); the triangle itself, its full
  // box, goes on to fine raster and interpolation.
  bool binned_;
  PixelRect bin_clip_;
  PixelRect walk_box(const SetupTriangle& t) const { return binned_ ? t.bbox.intersect(bin_clip_) : t.bbox; }
};

}  // namespace rastsim::sc
