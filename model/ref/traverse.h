// SPDX-License-Identifier: Apache-2.0
// Tiled traversal: coarse raster (tile walk with early-out / early-in) and fine raster
// (per-pixel coverage of partial tiles).
//
// - Tiles are raster.tile_size squares aligned to the framebuffer origin; the walk
//   visits, row by row, every tile that overlaps the triangle's clipped bounding box.
// - A tile's footprint is the tile clipped to that box. Each edge is linear, so over
//   the footprint's pixel centres its extremes lie at two opposite corners, chosen by
//   the signs of a and b: if some edge's maximum (with bias) is < 0 the tile is
//   rejected (early-out); if every edge's minimum is >= 0 it is accepted whole
//   (early-in, no per-pixel tests); otherwise it is partial and tested per pixel.
// - Fine raster walks a partial footprint row by row, stepping each edge value by
//   a * 2^F per pixel and b * 2^F per row (exact integers).
#pragma once

#include <cstdint>

#include "setup.h"

namespace rastsim {

enum class TileClass { Rejected, Accepted, Partial };

// Counters a hardware tile walker would keep.
struct TraversalCounters {
  uint64_t tiles_visited = 0, tiles_rejected = 0, tiles_accepted = 0, tiles_partial = 0;
  uint64_t pixel_tests = 0;  // per-pixel coverage tests (partial tiles only)
  uint64_t fragments = 0;    // covered pixels emitted
};

// The tile grid cells overlapping `bbox`, in tile units [tx0, tx1) x [ty0, ty1).
PixelRect tile_range(const PixelRect& bbox, int tile_size);
// Footprint of tile (tx, ty): the tile's pixels clipped to bbox.
PixelRect tile_footprint(const PixelRect& bbox, int tile_size, int tx, int ty);

// Early-out / early-in classification of one footprint.
TileClass classify_tile(const SetupTriangle& t, const PixelRect& footprint, int frac_bits);

// Coverage of one pixel (fill-rule bias included).
inline bool pixel_covered(const SetupTriangle& t, int px, int py, int frac_bits) {
  const int64_t sx = t.sample_x(px, frac_bits), sy = t.sample_y(py, frac_bits);
  for (const auto& e : t.edge)
    if (e.eval(sx, sy) + e.bias < 0) return false;
  return true;
}

// Fine raster of a partial footprint: calls emit(px, py) for each covered pixel in
// row-major order; returns the number of pixel tests made (= footprint area).
template <class Emit>
uint64_t fine_raster_partial(const SetupTriangle& t, const PixelRect& fp, int frac_bits, Emit&& emit) {
  const int64_t sx0 = t.sample_x(fp.x0, frac_bits), sy0 = t.sample_y(fp.y0, frac_bits);
  i128 row[3], step_x[3], step_y[3];
  for (int i = 0; i < 3; ++i) {
    row[i] = t.edge[i].eval(sx0, sy0) + t.edge[i].bias;
    step_x[i] = i128(t.edge[i].a) << frac_bits;
    step_y[i] = i128(t.edge[i].b) << frac_bits;
  }
  for (int py = fp.y0; py < fp.y1; ++py) {
    i128 e0 = row[0], e1 = row[1], e2 = row[2];
    for (int px = fp.x0; px < fp.x1; ++px) {
      if (e0 >= 0 && e1 >= 0 && e2 >= 0) emit(px, py);
      e0 += step_x[0];
      e1 += step_x[1];
      e2 += step_x[2];
    }
    for (int i = 0; i < 3; ++i) row[i] += step_y[i];
  }
  return static_cast<uint64_t>(fp.area());
}

// Whole-footprint emission of an accepted tile (no tests).
template <class Emit>
void fine_raster_accepted(const PixelRect& fp, Emit&& emit) {
  for (int py = fp.y0; py < fp.y1; ++py)
    for (int px = fp.x0; px < fp.x1; ++px) emit(px, py);
}

// The whole traversal of one set-up triangle: tile walk, classification, fine raster.
// emit(px, py) is called once per covered pixel, tile by tile (row-major tiles,
// row-major pixels inside each tile).
template <class Emit>
void traverse_triangle(const SetupTriangle& t, int tile_size, int frac_bits, TraversalCounters& c,
                       Emit&& emit) {
  const PixelRect tiles = tile_range(t.bbox, tile_size);
  for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
    for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
      const PixelRect fp = tile_footprint(t.bbox, tile_size, tx, ty);
      ++c.tiles_visited;
      switch (classify_tile(t, fp, frac_bits)) {
        case TileClass::Rejected: ++c.tiles_rejected; break;
        case TileClass::Accepted:
          ++c.tiles_accepted;
          c.fragments += static_cast<uint64_t>(fp.area());
          fine_raster_accepted(fp, emit);
          break;
        case TileClass::Partial:
          ++c.tiles_partial;
          c.pixel_tests += fine_raster_partial(t, fp, frac_bits, [&](int px, int py) {
            ++c.fragments;
            emit(px, py);
          });
          break;
      }
    }
  }
}

}  // namespace rastsim
