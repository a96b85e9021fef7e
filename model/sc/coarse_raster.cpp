// SPDX-License-Identifier: Apache-2.0
#include "sc/coarse_raster.h"

#include <algorithm>

namespace rastsim::sc {

void CoarseRaster::body() {
  TraversalCounters& c = ctx_.render.traversal;
  for (;;) {
    const SetupItem in = read(in_);
    if (pass_state(in, out_)) continue;
    const SetupTriangle& t = *in.work;
    const PixelRect tiles = tile_range(t.bbox, tile_size_);
    uint64_t visited = 0, cycles_done = 0;  // tiles classified; cycles of this walk spent
    for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
      for (int tx = tiles.x0; tx < tiles.x1; ++tx, ++visited) {
        const PixelRect fp = tile_footprint(t.bbox, tile_size_, tx, ty);
        ++c.tiles_visited;
        const TileClass cls = classify_tile(t, fp, frac_bits_);
        if (cls == TileClass::Rejected) {
          ++c.tiles_rejected;
          continue;
        }
        ++(cls == TileClass::Accepted ? c.tiles_accepted : c.tiles_partial);
        const uint64_t leave_at = visited / p_.coarse_tiles_per_cycle + 1;
        busy(leave_at - cycles_done);
        cycles_done = leave_at;
        write(out_, TileItem{nullptr, TileWork{in.work, fp, cls}});
      }
    }
    busy(std::max<uint64_t>(1, ceil_div(visited, p_.coarse_tiles_per_cycle)) - cycles_done);
  }
}

}  // namespace rastsim::sc
