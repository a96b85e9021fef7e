// SPDX-License-Identifier: Apache-2.0
// TileHeat: the busy cycles of one stage per screen tile (rastsim simulate --heatmap).
//
// - The grid is the framebuffer cut into raster.tile_size squares (the last row and
//   column may be partial).
// - A stage names the pixel its next busy() works for (Stage::attribute_to); the
//   cycles go to that pixel's tile. Coarse raster charges a walk's cycles to the tile
//   it writes at the end of them (the rejected tiles before it included), the trailing
//   cycles to the last tile it visited; fine raster, interpolation and ROP to the tile
//   of their batch (its footprint's or first pixel's).
// - Work that belongs to no tile (state commands, clears, the 2D port) is counted in
//   `unattributed`, so tiles + unattributed == the stage's busy cycles.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace rastsim::sc {

struct TileHeat {
  std::string stage;
  int tile_size = 16, tiles_x = 0, tiles_y = 0;  // px, tiles
  std::vector<uint64_t> cycles;                  // busy cycles, row-major tiles_x * tiles_y
  uint64_t unattributed = 0;                     // busy cycles of no tile

  TileHeat(std::string name, int width, int height, int tile)
      : stage(std::move(name)), tile_size(tile), tiles_x((width + tile - 1) / tile),
        tiles_y((height + tile - 1) / tile), cycles(size_t(tiles_x) * size_t(tiles_y), 0) {}
  // The tile of pixel (x, y), clamped to the grid (a batch never starts off screen,
  // but a bounding box of the 2D path may).
  int tile_of(int x, int y) const {
    const int tx = std::clamp(x / tile_size, 0, tiles_x - 1), ty = std::clamp(y / tile_size, 0, tiles_y - 1);
    return ty * tiles_x + tx;
  }
  void charge(int tile, uint64_t n) { (tile < 0 ? unattributed : cycles[size_t(tile)]) += n; }
  uint64_t total() const { return std::accumulate(cycles.begin(), cycles.end(), unattributed); }
};

}  // namespace rastsim::sc
