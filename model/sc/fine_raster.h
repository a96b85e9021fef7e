// SPDX-License-Identifier: Apache-2.0
// Fine raster: per-pixel coverage of partial tiles, whole-footprint emission of
// accepted ones (ref/fine_raster.h: fine_raster_partial, fine_raster_accepted).
//
// - A partial footprint of A pixels takes ceil(A S / fine.samples_per_cycle) cycles
//   (S = raster.samples: A S coverage tests); an accepted footprint takes
//   fine.accepted_tile_cycles (a full mask, no tests).
// - A span (raster.traversal = scanline) of n pixels takes fine.span_setup_cycles +
//   ceil(n / fine.span_pixels_per_cycle), no tests.
// - A tile's covered pixels leave as ONE transaction (a batch, row-major), so no event
//   exists per pixel; a tile with no covered pixel produces nothing.
// - Each pixel carries its coverage mask (S bits; 1 with one sample; full in an
//   accepted tile or a span). The batch stores runs, not pixels: consecutive pixels of a
//   row with the same mask are one PixelRun, as the walks find them (ref/fine_raster.h,
//   SpanEmitter), so a 16-pixel row of a tile is one store, not sixteen.
// - Counts pixel_tests, fragments, sample_tests, samples_covered and
//   pixels_partially_covered as ref/traverse.h does.
#pragma once

#include <vector>

#include "sc/coarse_raster.h"
#include "sc/recycler.h"

namespace rastsim::sc {

// Pixels x0 .. x1 - 1 of row y (x1 > x0), each with the same coverage mask.
struct PixelRun {
  int y = 0, x0 = 0, x1 = 0;
  uint32_t mask = 1;  // covered samples (bit s: sample s)
};
struct PixelBatch {
  LocalPtr<const SetupTriangle> tri;
  std::vector<PixelRun> runs;  // pixels of one tile with a covered sample, row-major
  uint64_t pixels = 0;         // sum of the runs' lengths
  bool hiz_accepted = false;   // its tile's (TileWork::hiz_accepted)
  std::shared_ptr<const std::vector<HizSpillWrite>> hiz_writes;  // its tile's (TileWork::hiz_writes)
  // Appends pixels x0 .. x1 - 1 of row y of mask m, after every pixel added so far
  // (row-major): it extends the last run when it continues it with the same mask.
  void add(int y, int x0, int x1, uint32_t m) {
    pixels += uint64_t(x1 - x0);
    if (!runs.empty()) {
      PixelRun& last = runs.back();
      if (last.y == y && last.x1 == x0 && last.mask == m) {
        last.x1 = x1;
        return;
      }
    }
    runs.push_back({y, x0, x1, m});
  }
  // The batch as an emitter of the walks (ref/fine_raster.h: a SpanEmitter).
  void operator()(int px, int py, uint32_t m) { add(py, px, px + 1, m); }
  void span(int py, int x0, int x1, uint32_t m) { add(py, x0, x1, m); }
};
using PixelItem = Item<LocalPtr<const PixelBatch>>;

class FineRaster : public Stage {
 public:
  static constexpr StageId kId = StageId::FineRaster;
  FineRaster(SimContext& ctx, const RasterState& arch, const TimingParams& p,
             Link<TileItem>& in, Link<PixelItem>& out,
           sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), frac_bits_(arch.coord_format.frac_bits), p_(p), in_(in), out_(out) {}

 private:
  void body() override;
  int frac_bits_;
  const TimingParams& p_;
  Link<TileItem>& in_;
  Link<PixelItem>& out_;
  Recycler<PixelBatch> batches_;  // no allocation a tile (sc/recycler.h)
};

}  // namespace rastsim::sc
