// SPDX-License-Identifier: Apache-2.0
// Fine raster: per-pixel coverage of a tile footprint that coarse raster found partial
// (ref/coarse_raster.h), and whole-footprint emission of an accepted one.
//
// - A partial footprint is walked row by row, stepping each edge value by a * 2^F per
//   pixel and b * 2^F per row (exact integers, i128).
#pragma once

#include <cstdint>

#include "ref/tri_setup.h"

namespace rastsim {

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

}  // namespace rastsim
