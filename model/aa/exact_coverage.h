// SPDX-License-Identifier: Apache-2.0
// Exact area coverage of a pixel by a set-up triangle (docs/exact-coverage.md).
//
// - The triangle is its snapped raw vertices t.x[], t.y[] (integers, s.I.F raw units
//   relative to the pixel t.origin_x/y); pixel px spans raw x in
//   [(px - origin_x) 2^F, (px - origin_x + 1) 2^F], likewise y.
// - The triangle is clipped against the square's four axis-aligned lines
//   (Sutherland-Hodgman) in exact rational arithmetic (GMP mpq_class), and the clipped
//   polygon's area taken by the shoelace formula: coverage = area / 2^(2F), an exact
//   rational in [0, 1]. No fill rule: the area of a boundary is zero.
// - classify_pixel_square decides the pixels that need no clipping with exact integer
//   edge tests at the square's corners: inside all three edges (coverage 1) or outside
//   one edge's closed half-plane (coverage 0).
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstdint>

#include "ref/raster_state.h"
#include "ref/tri_setup.h"

namespace rastsim {

// Exact area (raw^2 units) of the triangle with integer vertices (x[i], y[i]), either
// winding, intersected with the square [x0, x0 + side] x [y0, y0 + side].
mpq_class exact_square_area(const std::array<int64_t, 3>& x, const std::array<int64_t, 3>& y, int64_t x0,
                            int64_t y0, int64_t side);

// Exact coverage in [0, 1] of pixel (px, py) by t (frac_bits = raster.coord_format's F).
mpq_class exact_pixel_coverage(const SetupTriangle& t, int px, int py, int frac_bits);

enum class SquareClass { Outside, Inside, Boundary };

// Outside: the square lies in the closed outer half-plane of an edge (coverage 0).
// Inside: every corner is on or inside every edge (coverage 1). Boundary: neither (the
// coverage is below 1, and may be 0 when the triangle misses the square diagonally).
// Uses t.edge[] (interior E > 0), bias ignored.
SquareClass classify_pixel_square(const SetupTriangle& t, int px, int py, int frac_bits);

// Pixels whose square overlaps the triangle's vertex bounding box with positive area
// (a superset of the pixels of positive coverage); not clipped.
PixelRect pixels_under_triangle(const SetupTriangle& t, int frac_bits);

}  // namespace rastsim
