// SPDX-License-Identifier: Apache-2.0
// Line rasterization on pixel indices: the lecture notes' Bresenham, midpoint and DDA
// algorithms (docs/2d-lines.md), as pure geometry: emit(px, py) once a pixel, in drawing
// order from (x0, y0) to (x1, y1), both end pixels included. No clipping, no state.
//
// - The notes state each algorithm in one octant: 0 <= dy <= dx, drawn towards +x.
//   Every other line is mapped to it by symmetry: the major axis is the one with the
//   larger |delta| (x on a tie |dx| == |dy|); the walk steps the major coordinate by
//   sign(d_major) each pixel and the minor one by sign(d_minor) when the decision says
//   so. The decision variable is computed on |d_major|, |d_minor|, so a tie (the ideal
//   line exactly half way between two pixels) breaks the same way RELATIVE TO THE
//   DRAWING DIRECTION in every octant: Bresenham steps the minor axis (away from the
//   start's minor coordinate), midpoint does not. Reversing a line can therefore change
//   its tie pixels.
// - Bresenham: P1 = 2|dm| - |dM|; P >= 0 -> minor step, P += 2|dm| - 2|dM|; else P += 2|dm|.
// - Midpoint: d1 = 2|dm| - |dM| (the notes' d = F(x + 1, y + 1/2) doubled); d > 0 ->
//   minor step; d <= 0 -> major step only. Same increments as Bresenham.
// - DDA: m = d_minor / |d_major| (the minor change per major step of sign(d_major))
//   rounded once to the arithmetic (f32, f64, or fixed with
//   `frac_bits` fraction bits, round to nearest, ties to even); the minor coordinate
//   starts at the start pixel's index and accumulates += m in that arithmetic; the pixel
//   is floor(v + 0.5) evaluated in that arithmetic.
//
// Widths: pixel indices are int (|index| < 2^30); decision variables need 2 bits more
// than the larger |delta| and are int64_t.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "ref/fixed_point.h"

namespace rastsim {

enum class LineMethod { Diamond, Bresenham, Midpoint, Dda };
enum class DdaArith { F32, F64, Fixed };

const char* to_string(LineMethod m);
const char* to_string(DdaArith a);

// The octant mapping shared by the index methods: major/minor deltas and step signs.
struct LineOctant {
  bool x_major;         // |dx| >= |dy|
  int64_t d_major, d_minor;  // |delta| along the major and minor axis
  int step_major, step_minor;  // +1 or -1 (+1 for a zero delta)
  static LineOctant of(int x0, int y0, int x1, int y1) {
    const int64_t dx = int64_t(x1) - x0, dy = int64_t(y1) - y0;
    LineOctant o;
    o.x_major = std::llabs(dx) >= std::llabs(dy);
    o.d_major = o.x_major ? std::llabs(dx) : std::llabs(dy);
    o.d_minor = o.x_major ? std::llabs(dy) : std::llabs(dx);
    o.step_major = ((o.x_major ? dx : dy) < 0) ? -1 : 1;
    o.step_minor = ((o.x_major ? dy : dx) < 0) ? -1 : 1;
    return o;
  }
};

// Bresenham (tie_steps_minor = true) and midpoint (false): one incremental walk, the
// two differ only in whether a zero decision steps the minor axis.
template <class Emit>
void incremental_line(int x0, int y0, int x1, int y1, bool tie_steps_minor, Emit&& emit) {
  const LineOctant o = LineOctant::of(x0, y0, x1, y1);
  int64_t major = o.x_major ? x0 : y0, minor = o.x_major ? y0 : x0;
  int64_t p = 2 * o.d_minor - o.d_major;
  for (int64_t k = 0;; ++k) {
    if (o.x_major) emit(int(major), int(minor));
    else emit(int(minor), int(major));
    if (k == o.d_major) break;
    major += o.step_major;
    if (p > 0 || (tie_steps_minor && p == 0)) {
      minor += o.step_minor;
      p += 2 * o.d_minor - 2 * o.d_major;
    } else {
      p += 2 * o.d_minor;
    }
  }
}

template <class Emit>
void bresenham_line(int x0, int y0, int x1, int y1, Emit&& emit) {
  incremental_line(x0, y0, x1, y1, true, emit);
}
template <class Emit>
void midpoint_line(int x0, int y0, int x1, int y1, Emit&& emit) {
  incremental_line(x0, y0, x1, y1, false, emit);
}

// The DDA in floating point (T = float or double).
template <class T, class Emit>
void dda_line_float(int x0, int y0, int x1, int y1, Emit&& emit) {
  const LineOctant o = LineOctant::of(x0, y0, x1, y1);
  const int64_t dmin = o.x_major ? int64_t(y1) - y0 : int64_t(x1) - x0;
  // One rounding: both operands are exact in T for |delta| < 2^24 (f32) / 2^53 (f64).
  const T m = (o.d_major == 0) ? T(0) : T(dmin) / T(o.d_major);
  int64_t major = o.x_major ? x0 : y0;
  T v = T(o.x_major ? y0 : x0);
  for (int64_t k = 0;; ++k) {
    const int minor = int(std::floor(v + T(0.5)));
    if (o.x_major) emit(int(major), minor);
    else emit(minor, int(major));
    if (k == o.d_major) break;
    major += o.step_major;
    v = v + m;
  }
}

// The DDA in fixed point with `frac_bits` fraction bits (1..30).
template <class Emit>
void dda_line_fixed(int x0, int y0, int x1, int y1, int frac_bits, Emit&& emit) {
  const LineOctant o = LineOctant::of(x0, y0, x1, y1);
  const int64_t dmin = o.x_major ? int64_t(y1) - y0 : int64_t(x1) - x0;
  // m * 2^F rounded to nearest, ties to even (|m| <= 1, so it fits in F + 2 bits).
  const int64_t m =
      (o.d_major == 0) ? 0 : int64_t(div_round(i128(dmin) << frac_bits, o.d_major, Rounding::NearestEven));
  const int64_t half = int64_t{1} << (frac_bits - 1);
  int64_t major = o.x_major ? x0 : y0;
  int64_t v = int64_t(o.x_major ? y0 : x0) << frac_bits;
  for (int64_t k = 0;; ++k) {
    const int minor = int((v + half) >> frac_bits);  // arithmetic shift = floor
    if (o.x_major) emit(int(major), minor);
    else emit(minor, int(major));
    if (k == o.d_major) break;
    major += o.step_major;
    v += m;
  }
}

template <class Emit>
void dda_line(int x0, int y0, int x1, int y1, DdaArith arith, int frac_bits, Emit&& emit) {
  switch (arith) {
    case DdaArith::F32: dda_line_float<float>(x0, y0, x1, y1, emit); break;
    case DdaArith::F64: dda_line_float<double>(x0, y0, x1, y1, emit); break;
    case DdaArith::Fixed: dda_line_fixed(x0, y0, x1, y1, frac_bits, emit); break;
  }
}

// ---- The diamond-exit rule (Direct3D 11 / OpenGL aliased lines) ----
// On snapped sub-pixel endpoints (raw, `frac_bits` fraction bits, absolute pixel
// coordinates). Pixel (px, py) has the diamond |x - cx| + |y - cy| < 1/2 around its
// centre (cx, cy) = (px + 1/2, py + 1/2), plus, of its boundary, the two lower edges and
// the bottom corner (y grows downwards), and for a y-major line also the right corner;
// the upper edges and the top and left corners are never in (nor the right corner of an
// x-major line). A line is x-major when |dx| >= |dy|. The line lights a pixel when,
// travelling from start to end, it exits that area: the segment meets the area and its
// end point is not inside it. So a line ending inside a diamond does not light that
// pixel, and a strip draws each shared vertex once.
// diamond_exits: the exact test for one pixel (i128 arithmetic; raw |coordinates| < 2^40).
bool diamond_exits(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t px, int64_t py, int frac_bits);
// Every lit pixel, in drawing order (along the major axis from the start; within one
// major step along the minor direction of travel).
template <class Emit>
void diamond_line(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int frac_bits, Emit&& emit) {
  const bool x_major = std::llabs(x1 - x0) >= std::llabs(y1 - y0);
  const int64_t a0 = x_major ? x0 : y0, a1 = x_major ? x1 : y1;  // major axis
  const int64_t b0 = x_major ? y0 : x0, b1 = x_major ? y1 : x1;  // minor axis
  const int step = (a1 < a0) ? -1 : 1, bstep = (b1 < b0) ? -1 : 1;
  const int64_t first = (a0 >> frac_bits) - step, last = (a1 >> frac_bits) + step;
  for (int64_t m = first;; m += step) {
    // The minor coordinate of the line at this column's centre, floored: the diamonds
    // it can exit are within one pixel of it (|slope| <= 1).
    const int64_t mc = (m << frac_bits) + (int64_t{1} << (frac_bits - 1));
    int64_t bc = b0;
    if (a1 != a0) {
      const i128 num = i128(b0) * (a1 - a0) + i128(mc - a0) * (b1 - b0), den = a1 - a0;
      bc = int64_t(den > 0 ? div_round(num, den, Rounding::Floor) : div_round(-num, -den, Rounding::Floor));
    }
    const int64_t n0 = (bc >> frac_bits) - bstep;
    for (int k = 0; k < 3; ++k) {
      const int64_t n = n0 + k * bstep;
      const int64_t px = x_major ? m : n, py = x_major ? n : m;
      if (diamond_exits(x0, y0, x1, y1, px, py, frac_bits)) emit(int(px), int(py));
    }
    if (m == last) break;
  }
}

// Pixels where Bresenham and midpoint differ on a line of these deltas: the ideal line
// is exactly half way between two pixels at column k of the walk when
// 2 |dm| k = |dM| (mod 2 |dM|). With g = gcd(|dM|, |dm|) and b = |dM| / g, that has
// one solution per b columns when b is even and none when b is odd, so the count over
// k = 1..|dM| is (b even ? g : 0). (docs/2d-lines.md derives it.)
int64_t bresenham_midpoint_ties(int64_t d_major, int64_t d_minor);

}  // namespace rastsim
