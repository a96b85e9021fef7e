// SPDX-License-Identifier: Apache-2.0
// Polygon fill by the lecture notes' scanline algorithm (docs/2d-shapes.md), as pure
// geometry on snapped vertices (raw fixed point, `frac_bits` fraction bits, absolute
// pixel coordinates), exact integer arithmetic.
//
// - Scanlines run through the pixel centres, y = py + 1/2. An edge meets the scanlines
//   whose y lies in [y_top, y_bottom) of the edge (half-open: a vertex on a scanline
//   counts once, horizontal edges never).
// - Edge table: edges sorted by their first scanline; the active edge table gains them
//   there and drops them after their last.
// - On a scanline each active edge gives the first pixel whose centre lies at or right
//   of its intersection, c = ceil(x_int - 1/2) (exact), and a direction (+1 downwards,
//   -1 upwards). Sorted by c, pixel px is inside when the edges with c <= px have odd
//   count (even-odd, the notes' odd parity) or a non-zero direction sum (non-zero).
// - So a centre exactly on an edge is inside when the edge is a left edge (the region
//   lies to its right) and outside on a right edge; on a horizontal edge it is inside
//   when the edge is a top edge: the triangle pipeline's top-left rule. Polygons that
//   share edges cover every pixel once.
// Widths: products of two raw coordinates need 2N + 2 bits (i128).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "ref/2d/circle_raster.h"

namespace rastsim {

enum class PolygonRule { EvenOdd, NonZero };

// Spans of the filled polygon, rows top to bottom, spans left to right within a row.
std::vector<PixelSpan> fill_polygon(const std::vector<std::pair<int64_t, int64_t>>& vertices, int frac_bits,
                                    PolygonRule rule);

const char* to_string(PolygonRule r);

}  // namespace rastsim
