// SPDX-License-Identifier: Apache-2.0
#include "sc/fine_raster.h"

namespace rastsim::sc {

void FineRaster::body() {
  TraversalCounters& c = ctx_.render.traversal;
  for (;;) {
    const TileItem in = read(in_);
    if (pass_state(in, out_)) continue;
    const TileWork& tile = in.work;
    std::shared_ptr<PixelBatch> batch = batches_.take();
    batch->tri = tile.tri;
    batch->pixels.clear();  // keeps its capacity
    const int samples = tile.tri->samples;
    auto emit = [&](int px, int py, uint32_t m) { batch->pixels.push_back({px, py, m}); };
    uint64_t cost = 0;
    if (tile.span) {  // one sample (the config rejects scanline with raster.samples > 1)
      fine_raster_accepted(tile.footprint, emit);
      c.count_accepted(tile.footprint.area(), 1);
      cost = p_.fine_span_cycles(uint64_t(tile.footprint.area()));
    } else if (tile.cls == TileClass::Accepted) {
      fine_raster_accepted(tile.footprint, emit, tile.tri->full_mask());
      c.count_accepted(tile.footprint.area(), samples);
      cost = p_.fine_accepted_cycles();
    } else {
      const uint64_t tests = fine_raster_partial(*tile.tri, tile.footprint, frac_bits_, [&](int px, int py, uint32_t m) {
        c.count_pixel(m, samples);
        emit(px, py, m);
      });
      c.count_tests(tests, samples);
      cost = p_.fine_partial_cycles(tests, samples);
    }
    attribute_to(tile.footprint.x0, tile.footprint.y0);
    busy(cost);
    if (!batch->pixels.empty()) write(out_, PixelItem{nullptr, std::move(batch)});
  }
}

}  // namespace rastsim::sc
