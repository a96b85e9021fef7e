// SPDX-License-Identifier: Apache-2.0
// Scanline traversal: the lecture notes' "screen coordinate setup" on the snapped
// vertices of a set-up triangle, in f32, f64 or fixed point (raster.scanline_arith).
//
// Coordinates: "centre coordinates", in pixels, where pixel (px, py) has its centre at
// the integers (px, py): X = (raw + origin * 2^F - 2^(F-1)) / 2^F, formed exactly in
// int64 and converted once to the arithmetic (f32: rounds to 24 bits; f64: exact for
// |raw| < 2^53; fixed: the raw integer itself, F fraction bits).
//
// - Sort the vertices by y: A (top), B, C (bottom); ties in y keep setup's order.
// - Gradients dx/dy of AB, BC, AC (the long edge), each one division in the arithmetic
//   (fixed: round(dx * 2^F / dy) to nearest even, F fraction bits; an edge with dy = 0
//   has no rows and no gradient).
// - The x-intersection at the first pixel-centre row at or below the edge's top vertex,
//   y0 = ceil(y_top): x = x_top + (dx/dy) * (y0 - y_top) (fixed: the product rounded to
//   nearest even back to F fraction bits); then x += dx/dy for each following row.
// - Rows y with y_A <= y < y_B use AB and AC, rows y_B <= y < y_C use BC and AC (a row
//   through a vertex belongs to the lower part; the bottom vertex's row is excluded,
//   the top one's included: the top-left rule's top edge / bottom edge, since a
//   horizontal edge has no rows of its own).
// - Which of the two edges is left comes from the exact sign of the doubled area
//   (which side of AC B lies), not from comparing the inexact intersections.
// - Span endpoint to pixels (top-left convention on the span's ends): pixel px is in
//   the span when x_left <= px < x_right, i.e. px from ceil(x_left) to ceil(x_right) - 1
//   (a centre exactly on the left edge is covered, on the right edge not), each
//   ceil evaluated exactly on the value the arithmetic holds.
// - Rows and columns are clamped to the triangle's clipped bounding box t.bbox (no
//   pixel outside the viewport/scissor, no out-of-bounds write); rows above the box are
//   stepped but not reported.
// With exact arithmetic this is the edge-function top-left rule; the roundings of the
// conversion, the division, the start product and the accumulation are what makes it
// differ (docs/traversal.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "ref/2d/line_raster.h"
#include "ref/tri_setup.h"

namespace rastsim {

namespace scanline_detail {

// The exact side test: true when B lies left of the long edge A->C on screen (y down),
// i.e. AB/BC form the left side of the spans.
inline bool mid_is_left(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t cx, int64_t cy) {
  // cross(C - A, B - A) > 0 means B is to the left of A->C when y grows downward
  // (A->C straight down, B at smaller x: (0)(by-ay) - (cy-ay)(bx-ax) > 0).
  const i128 cross = i128(cx - ax) * (by - ay) - i128(cy - ay) * (bx - ax);
  return cross > 0;
}

// One edge walker in arithmetic T (float or double): x at the current row.
template <class T>
struct FloatEdge {
  T x = 0, m = 0;
  void start(T xt, T yt, T xb, T yb, int64_t row) {
    m = (xb - xt) / (yb - yt);
    x = xt + m * (T(row) - yt);
  }
  void step() { x = x + m; }
  // ceil(x) as a pixel index, clamped to [lo, hi] (the bbox plus one: NaN/inf safe).
  int64_t ceil_px(int64_t lo, int64_t hi) const {
    const double v = std::ceil(double(x));
    if (!(v >= double(lo))) return lo;
    if (v > double(hi)) return hi;
    return int64_t(v);
  }
};

// The fixed-point edge walker: x and m in raw units with F fraction bits (int64; |x| <
// 2^(I+F+1), m rounded to nearest even).
struct FixedEdge {
  int64_t x = 0, m = 0;
  int F = 0;
  void start(int64_t xt, int64_t yt, int64_t xb, int64_t yb, int64_t row, int frac_bits) {
    F = frac_bits;
    m = int64_t(div_round(i128(xb - xt) << F, yb - yt, Rounding::NearestEven));
    const i128 dy_row = (i128(row) << F) - yt;  // raw, >= 0
    x = xt + int64_t(shift_right_round(i128(m) * dy_row, F, Rounding::NearestEven));
  }
  void step() { x += m; }
  int64_t ceil_px(int64_t lo, int64_t hi) const {
    const int64_t v = -((-x) >> F);  // ceil(x / 2^F); >> is floor on int64
    return std::clamp(v, lo, hi);
  }
};

}  // namespace scanline_detail

// Calls row(py, x0, x1) for every pixel row of the triangle inside t.bbox, top to
// bottom, with the span's pixels [x0, x1) clamped to the box (x0 >= x1: empty span).
template <class Row>
void scanline_spans(const SetupTriangle& t, DdaArith arith, int frac_bits, Row&& row) {
  using namespace scanline_detail;
  const int F = frac_bits;
  // Centre coordinates, raw (F fraction bits), exact.
  std::array<int64_t, 3> X, Y;
  for (int i = 0; i < 3; ++i) {
    X[i] = t.x[i] + (t.origin_x << F) - (int64_t{1} << (F - 1));
    Y[i] = t.y[i] + (t.origin_y << F) - (int64_t{1} << (F - 1));
  }
  std::array<int, 3> o{0, 1, 2};
  std::stable_sort(o.begin(), o.end(), [&](int a, int b) { return Y[a] < Y[b]; });
  const int a = o[0], b = o[1], c = o[2];
  const bool b_left = mid_is_left(X[a], Y[a], X[b], Y[b], X[c], Y[c]);
  // First row at or below raw y: ceil(y / 2^F); rows are pixel indices.
  auto first_row = [&](int64_t y) { return -((-y) >> F); };
  const int64_t lo = t.bbox.x0, hi = t.bbox.x1;
  const int64_t ya = first_row(Y[a]), yb = first_row(Y[b]);
  // Row py is in the triangle while py * 2^F < Y of the part's bottom vertex.
  auto before = [&](int64_t py, int64_t y) { return (i128(py) << F) < y; };

  auto walk = [&](auto& long_edge, auto& short_edge, auto start_edge) {
    start_edge(long_edge, a, c, ya);
    int64_t py = ya;
    for (int part = 0; part < 2; ++part) {
      const int top = part == 0 ? a : b, bot = part == 0 ? b : c;
      if (part == 1) {
        // Rows of the upper part that never ran still advance the long edge.
        for (; py < yb; ++py) long_edge.step();
        py = std::max(py, yb);
      }
      if (Y[bot] == Y[top]) continue;  // horizontal short edge: no rows
      start_edge(short_edge, top, bot, py);
      for (; before(py, Y[bot]); ++py) {
        if (py >= t.bbox.y1) return;
        if (py >= t.bbox.y0) {
          const auto& l = b_left ? short_edge : long_edge;
          const auto& r = b_left ? long_edge : short_edge;
          const int64_t x0 = l.ceil_px(lo, hi), x1 = r.ceil_px(lo, hi);
          row(int(py), int(x0), int(x1));
        }
        long_edge.step();
        short_edge.step();
      }
    }
  };

  switch (arith) {
    case DdaArith::Fixed: {
      FixedEdge le, se;
      walk(le, se, [&](FixedEdge& e, int top, int bot, int64_t py) { e.start(X[top], Y[top], X[bot], Y[bot], py, F); });
      break;
    }
    case DdaArith::F32:
    case DdaArith::F64: {
      auto run = [&](auto zero) {
        using T = decltype(zero);
        const T scale = T(std::ldexp(1.0, -F));  // exact power of two
        FloatEdge<T> le, se;
        walk(le, se, [&](FloatEdge<T>& e, int top, int bot, int64_t py) {
          e.start(T(X[top]) * scale, T(Y[top]) * scale, T(X[bot]) * scale, T(Y[bot]) * scale, py);
        });
      };
      if (arith == DdaArith::F32) run(0.0f);
      else run(0.0);
      break;
    }
  }
}

}  // namespace rastsim
