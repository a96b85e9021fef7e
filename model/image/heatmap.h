// SPDX-License-Identifier: Apache-2.0
// The tile heatmap picture of `rastsim simulate --heatmap` (docs/timeline.md).
//
// - The rendered frame, dimmed to 35 %, scaled up by a whole factor to at least 640 px
//   wide, with every tile of non-zero cost painted in a colour map (viridis, linear
//   from 0 to the costliest tile) at 65 % opacity; tiles of zero cost stay clear.
// - A colour bar on the right with tick labels in cycles, and a legend above: what is
//   counted, the tile size, the maximum and the total. Text in the 2D engine's font
//   (ref/2d/font.h), so no font library is needed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ref/framebuffer.h"

namespace rastsim {

struct TileGrid {
  int tile_size = 16, tiles_x = 0, tiles_y = 0;  // px, tiles
  std::vector<uint64_t> cycles;                  // row-major tiles_x * tiles_y
};

// Viridis at t in [0, 1] (clamped), as R G B; five control points, linear between.
void colormap_viridis(double t, uint8_t rgb[3]);

// The picture (see above) as an RGBA framebuffer; `title` is the legend's first line.
Framebuffer draw_heatmap(const Framebuffer& frame, const TileGrid& grid, const std::string& title);

}  // namespace rastsim
