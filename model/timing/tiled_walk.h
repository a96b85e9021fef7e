// SPDX-License-Identifier: Apache-2.0
// The coarse walker's cycle model for raster.traversal = tiled, as the RTL walker does it
// (rtl/rast_coarse_raster.sv). Stateful: the SystemC coarse raster, the analytic
// estimate and the RTL testbench feed it the same walk and read the same cycles.
#pragma once

#include <algorithm>
#include <cstdint>

namespace rastsim {

// Each cycle the walker classifies a window of T = coarse.tiles_per_cycle tiles in walk
// order and sends at most one, the window's first surviving tile; the next window starts
// at the tile after it. Feed it every tile in walk order; visit() returns the walk cycle
// (from 1) in which a surviving tile leaves.
struct TiledWalk {
  uint64_t tiles_per_cycle = 1;
  uint64_t window = 1, window_start = 0;  // the current cycle and its window's first tile
  uint64_t visited = 0, last_sent = 0;    // tiles seen; the cycle of the last tile sent
  uint64_t visit(bool survives) {
    while (visited >= window_start + tiles_per_cycle) {  // that window found nothing
      ++window;
      window_start += tiles_per_cycle;
    }
    ++visited;
    if (!survives) return 0;
    last_sent = window;
    window_start = visited;  // the next window starts after this tile, next cycle
    return window++;
  }
  // The walk cycle whose window holds the next tile visit() will see.
  uint64_t next_window() const {
    uint64_t w = window, start = window_start;
    for (; visited >= start + tiles_per_cycle; start += tiles_per_cycle) ++w;
    return w;
  }
  // The next tile starts a window in walk cycle `cycle` (> next_window()): the walker held
  // it there (Hi-Z's interlock, docs/depth-culling.md), the cycles between spent waiting.
  void restart(uint64_t cycle) {
    window = cycle;
    window_start = visited;
  }
  // The walk's cycles: the window holding its last tile, or the cycle its last tile
  // was sent in when that was the last one; at least one.
  uint64_t cycles() const { return std::max<uint64_t>(1, window_start < visited ? window : last_sent); }
};

}  // namespace rastsim
