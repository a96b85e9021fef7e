// SPDX-License-Identifier: Apache-2.0
// Goldens for the index line methods (ref/2d/line_raster.h), written from dx, dy directly
// in integer arithmetic, not through LineOctant: shared by tb/test_line_raster.cpp and
// the stability searches (tb/stability/test_dda_lines.cpp).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

namespace rastsim::testing {

using Pixels = std::vector<std::pair<int, int>>;

inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  return (a >= 0) ? a / b : -((-a + b - 1) / b);
}

// The exact rule, stated per step k = 0..n of the major axis: the minor offset from the
// start is round(k * |d_minor| / n), a tie rounded up (towards the end's minor
// coordinate) when `tie_up`.
inline Pixels exact_index_line(int x0, int y0, int x1, int y1, bool tie_up) {
  const int64_t dx = x1 - x0, dy = y1 - y0;
  const bool xmaj = std::llabs(dx) >= std::llabs(dy);
  const int64_t n = xmaj ? std::llabs(dx) : std::llabs(dy), dm = xmaj ? std::llabs(dy) : std::llabs(dx);
  Pixels out;
  for (int64_t k = 0; k <= n; ++k) {
    int64_t off = 0;
    if (n > 0) off = tie_up ? floor_div(2 * k * dm + n, 2 * n) : floor_div(2 * k * dm + n - 1, 2 * n);
    const int64_t a = (xmaj ? dx : dy) < 0 ? -k : k;            // along the major axis
    const int64_t b = (xmaj ? dy : dx) < 0 ? -off : off;        // along the minor axis
    out.emplace_back(int(xmaj ? x0 + a : x0 + b), int(xmaj ? y0 + b : y0 + a));
  }
  return out;
}

// The exact DDA: minor = floor(start + k * d_minor / n + 1/2), in integers.
inline Pixels exact_dda_line(int x0, int y0, int x1, int y1) {
  const int64_t dx = x1 - x0, dy = y1 - y0;
  const bool xmaj = std::llabs(dx) >= std::llabs(dy);
  const int64_t n = xmaj ? std::llabs(dx) : std::llabs(dy), dmin = xmaj ? dy : dx, v0 = xmaj ? y0 : x0;
  Pixels out;
  for (int64_t k = 0; k <= n; ++k) {
    const int64_t v = (n == 0) ? v0 : floor_div(2 * v0 * n + 2 * k * dmin + n, 2 * n);
    const int64_t a = (xmaj ? dx : dy) < 0 ? -k : k;
    out.emplace_back(int(xmaj ? x0 + a : v), int(xmaj ? v : y0 + a));
  }
  return out;
}

// Whether step k of the exact DDA of a line with these deltas is a tie (the exact
// minor coordinate is an integer + 1/2): 2 k d_minor + n = 0 (mod 2n).
inline bool exact_dda_tie(int64_t n, int64_t d_minor, int64_t k) {
  return n > 0 && (2 * k * std::llabs(d_minor) + n) % (2 * n) == 0;
}

}  // namespace rastsim::testing
