// SPDX-License-Identifier: Apache-2.0
#include "sc/fine_raster.h"

#include "sc/hiz_interlock.h"

namespace rastsim::sc {

void FineRaster::body() {
  TraversalCounters& c = ctx_.render.traversal;
  for (;;) {
    const TileItem in = read(in_);
    if (pass_state(in, out_)) {
      if (ctx_.hiz_interlock) ctx_.hiz_interlock->fine(false, now());
      continue;
    }
    const TileWork& tile = in.work;
    LocalPtr<PixelBatch> batch = batches_.take();
    batch->tri = tile.tri;
    batch->runs.clear();  // keeps its capacity
    batch->pixels = 0;
    batch->hiz_accepted = tile.hiz_accepted;
    batch->hiz_writes = tile.hiz_writes;
    const int samples = tile.tri->samples;
    uint64_t cost = 0;
    if (tile.span) {  // one sample (the config rejects scanline with raster.samples > 1)
      fine_raster_accepted(tile.footprint, *batch);
      c.count_accepted(tile.footprint.area(), 1);
      cost = p_.fine_span_cycles(uint64_t(tile.footprint.area()));
    } else if (tile.cls == TileClass::Accepted) {
      fine_raster_accepted(tile.footprint, *batch, tile.tri->full_mask());
      c.count_accepted(tile.footprint.area(), samples);
      cost = p_.fine_accepted_cycles();
    } else {
      // counted(): each pixel or run counted as the reference's walk counts it.
      const uint64_t tests = fine_raster_partial(*tile.tri, tile.footprint, frac_bits_, counted(c, samples, *batch));
      c.count_tests(tests, samples);
      cost = p_.fine_partial_cycles(tests, samples);
    }
    // Hi-Z's interlock: a tile with no covered pixel ends here, at its busy's end, recorded
    // before it (sc/hiz_interlock.h: an end is known by SystemC time end - 1).
    if (ctx_.hiz_interlock) ctx_.hiz_interlock->fine(batch->pixels == 0, now() + cost);
    attribute_to(tile.footprint.x0, tile.footprint.y0);
    busy(cost);
    if (batch->pixels != 0) write(out_, PixelItem{nullptr, std::move(batch)});
  }
}

}  // namespace rastsim::sc
