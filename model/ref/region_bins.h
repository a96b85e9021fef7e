// SPDX-License-Identifier: Apache-2.0
// Screen regions for the parallel reference pipeline (render --threads N, pipeline.h).
//
// - The screen is cut into square regions of `size` px. Triangles are binned to every
//   region their clipped bounding box overlaps, in triangle order, and each region is
//   rasterized by one thread at a time: a pixel belongs to one region, so its ROP sees
//   the triangles in scene order, as with one thread, and the framebuffer is the same
//   bit for bit.
// - `size` is a multiple of the traversal tile (raster.tile_size, or the first level of
//   raster.hier_levels) and of the framebuffer's storage tile: a region holds whole
//   traversal tiles, so walking a triangle's box clipped to each region visits exactly
//   the tiles (and footprints) one walk of the whole box does and the counters add up;
//   and a storage tile is written by one thread only (its allocation is the only shared
//   step, framebuffer.cpp).
#pragma once

#include <algorithm>
#include <exception>
#include <numeric>
#include <thread>
#include <vector>

#include "ref/raster_state.h"

namespace rastsim {

struct RegionGrid {
  int size = 64;       // px, square
  int nx = 1, ny = 1;  // regions across and down

  // `align`: every length (px) the region side must be a multiple of; `min_size`: the
  // smallest side worth a bin (px).
  RegionGrid(int width, int height, const std::vector<int>& align, int min_size = 64) {
    int base = 1;
    for (int a : align) base = std::lcm(base, std::max(a, 1));
    size = base * ((min_size + base - 1) / base);
    nx = std::max(1, (width + size - 1) / size);
    ny = std::max(1, (height + size - 1) / size);
  }
  int count() const { return nx * ny; }
  PixelRect rect(int r) const {
    const int x = (r % nx) * size, y = (r / nx) * size;
    return {x, y, x + size, y + size};
  }
  // Region of pixel (x, y), which lies on the screen.
  int region_of(int x, int y) const { return (y / size) * nx + x / size; }
  // The regions a box on the screen overlaps, [x0, x1) x [y0, y1) in region units.
  PixelRect range(const PixelRect& box) const {
    return {box.x0 / size, box.y0 / size, (box.x1 - 1) / size + 1, (box.y1 - 1) / size + 1};
  }
};

// Runs body(t) for t in [0, n) on n threads (t = 0 on the caller's) and joins them; the
// first exception in thread order is rethrown after all have finished.
template <class Body>
void run_on_threads(int n, Body&& body) {
  std::vector<std::exception_ptr> err(size_t(std::max(n, 1)));
  auto guarded = [&](int t) {
    try {
      body(t);
    } catch (...) {
      err[size_t(t)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(guarded, t);
  guarded(0);
  for (auto& th : pool) th.join();
  for (auto& e : err)
    if (e) std::rethrow_exception(e);
}

}  // namespace rastsim
