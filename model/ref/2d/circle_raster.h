// SPDX-License-Identifier: Apache-2.0
// Circles by the lecture notes' midpoint algorithm (docs/2d-shapes.md), as pure
// geometry: integer centre and radius, no clipping, no state.
//
// - One octant is walked from (0, r) while x < y: d = F(x + 1, y - 1/2) with
//   F(x, y) = x^2 + y^2 - r^2; SE (x + 1, y - 1) when d >= 0, E (x + 1, y) when d < 0;
//   d += 2x + 3 after E, d += 2(x - y) + 5 after SE (x, y before the step). The
//   decision is kept as 4d, an integer: 4d0 = 5 - 4r.
// - Every octant point (x, y) gives the eight pixels (cx +- x, cy +- y), (cx +- y, cy +- x);
//   the outline is their union, each pixel once (axes, diagonals and r = 0 give
//   coinciding images), in row-major order.
// - The filled circle is, on every row of the outline, the span between its leftmost
//   and rightmost outline pixel, half-open [x0, x1), each pixel once.
// Widths: 4d needs 2 bits more than r^2; r up to 2^20 keeps everything in int64_t.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace rastsim {

// The notes' octant walk: the points (x, y), 0 <= x, of the octant starting at (0, r).
std::vector<std::pair<int64_t, int64_t>> midpoint_circle_octant(int64_t r);

struct PixelSpan {
  int y, x0, x1;  // pixels [x0, x1) of row y
  bool operator==(const PixelSpan&) const = default;
};

// Outline pixels, each once, row-major. r >= 0.
std::vector<std::pair<int, int>> circle_outline(int cx, int cy, int r);
// Filled circle as spans, rows top to bottom.
std::vector<PixelSpan> circle_fill(int cx, int cy, int r);

// Arc: the outline pixels (circle_outline, same order) whose direction from the centre
// lies in the sector swept counter-clockwise ON SCREEN from a0 to a1 degrees (from +x;
// the direction of angle t is (cos t, -sin t) with y down). sweep = a1 - a0 >= 0; 360
// or more is the whole circle. Exact rule: each end direction is the integer vector
// round(2^24 * (cos t, sin t)) (double, round to nearest), and a pixel offset q = (x, -y)
// is inside by integer cross products (both end rays included; a pixel on the ray
// opposite an end direction is not on that end's ray). The centre pixel (r = 0) is drawn.
std::vector<std::pair<int, int>> arc_outline(int cx, int cy, int r, double a0_deg, double a1_deg);
// The end direction of angle t degrees: round(2^24 * (cos t, sin t)), y up.
std::pair<int64_t, int64_t> arc_direction(double deg);
// Whether offset (x, y) (screen, y down) lies in the sector from direction d0 to d1
// (y up) of sweep `sweep_deg` in [0, 360).
bool arc_contains(std::pair<int64_t, int64_t> d0, std::pair<int64_t, int64_t> d1, double sweep_deg, int64_t x,
                  int64_t y);

}  // namespace rastsim
