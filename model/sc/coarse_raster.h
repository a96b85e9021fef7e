// SPDX-License-Identifier: Apache-2.0
// Coarse raster: the tile walk of one set-up triangle with early-out and early-in
// (ref/coarse_raster.h: tile_range, tile_footprint, classify_tile).
//
// - Visits every tile overlapping the triangle's clipped bounding box, row by row, at
//   coarse.tiles_per_cycle tiles a cycle: the walk of V tiles takes
//   max(1, ceil(V / tiles_per_cycle)) cycles.
// - Rejected tiles go no further; an accepted or partial tile is written to the tile
//   FIFO at the end of the cycle that classified it (tile i, counted from 0 in walk
//   order, leaves at cycle floor(i / tiles_per_cycle) + 1 of the walk).
// - Counts tiles_visited / rejected / accepted / partial.
#pragma once

#include "ref/coarse_raster.h"
#include "sc/tri_setup.h"

namespace rastsim::sc {

struct TileWork {
  std::shared_ptr<const SetupTriangle> tri;
  PixelRect footprint;  // the tile clipped to the triangle's bounding box
  TileClass cls = TileClass::Partial;  // Accepted or Partial
};
using TileItem = Item<TileWork>;

class CoarseRaster : public Stage {
 public:
  CoarseRaster(sc_core::sc_module_name name, SimContext& ctx, const RasterState& arch, const TimingParams& p,
               Link<SetupItem>& in, Link<TileItem>& out)
      : Stage(name, ctx, 3), tile_size_(arch.tile_size), frac_bits_(arch.coord_format.frac_bits), p_(p),
        in_(in), out_(out) {}

 private:
  void body() override;
  int tile_size_, frac_bits_;
  const TimingParams& p_;
  Link<SetupItem>& in_;
  Link<TileItem>& out_;
};

}  // namespace rastsim::sc
