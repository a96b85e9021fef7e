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
//   accepted tile or a span).
// - Counts pixel_tests, fragments, sample_tests, samples_covered and
//   pixels_partially_covered as ref/traverse.h does.
#pragma once

#include <vector>

#include "sc/coarse_raster.h"
#include "sc/recycler.h"

namespace rastsim::sc {

struct Pixel {
  int x = 0, y = 0;
  uint32_t mask = 1;  // covered samples (bit s: sample s)
};
struct PixelBatch {
  std::shared_ptr<const SetupTriangle> tri;
  std::vector<Pixel> pixels;  // pixels of one tile with a covered sample, row-major
};
using PixelItem = Item<std::shared_ptr<const PixelBatch>>;

class FineRaster : public Stage {
 public:
  FineRaster(sc_core::sc_module_name name, SimContext& ctx, const RasterState& arch, const TimingParams& p,
             Link<TileItem>& in, Link<PixelItem>& out)
      : Stage(name, ctx, 4), frac_bits_(arch.coord_format.frac_bits), p_(p), in_(in), out_(out) {}

 private:
  void body() override;
  int frac_bits_;
  const TimingParams& p_;
  Link<TileItem>& in_;
  Link<PixelItem>& out_;
  Recycler<PixelBatch> batches_;  // no allocation a tile (sc/recycler.h)
};

}  // namespace rastsim::sc
