// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/line_raster.h"

#include <numeric>

namespace rastsim {

const char* to_string(LineMethod m) {
  switch (m) {
    case LineMethod::Diamond: return "diamond";
    case LineMethod::Bresenham: return "bresenham";
    case LineMethod::Midpoint: return "midpoint";
    case LineMethod::Dda: return "dda";
  }
  return "?";
}

const char* to_string(DdaArith a) {
  switch (a) {
    case DdaArith::F32: return "f32";
    case DdaArith::F64: return "f64";
    case DdaArith::Fixed: return "fixed";
  }
  return "?";
}

namespace {

// A rational parameter t = num / den along the segment, den > 0.
struct Frac {
  i128 num, den;
};
bool less(const Frac& a, const Frac& b) { return a.num * b.den < b.num * a.den; }

// Whether the point (u, v) / den (relative to the pixel centre, in units where half a
// pixel is h) lies in the diamond test area.
bool in_area(i128 u, i128 v, i128 den, i128 h, bool y_major) {
  const i128 au = u < 0 ? -u : u, av = v < 0 ? -v : v, hd = h * den;
  if (au + av < hd) return true;
  if (au + av == hd && v > 0) return true;      // lower edges and the bottom corner
  return y_major && u == hd && v == 0;          // the right corner, y-major lines only
}

}  // namespace

bool diamond_exits(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t px, int64_t py, int frac_bits) {
  // Work in units of 2^-(F+1) pixel: the centre and half a pixel are integers.
  const i128 h = i128(1) << frac_bits;
  const i128 cx = (2 * i128(px) + 1) * h, cy = (2 * i128(py) + 1) * h;
  const i128 ax = 2 * i128(x0) - cx, ay = 2 * i128(y0) - cy;  // start, relative to the centre
  const i128 dx = 2 * (i128(x1) - x0), dy = 2 * (i128(y1) - y0);
  const bool y_major = (dx < 0 ? -dx : dx) < (dy < 0 ? -dy : dy);
  if (in_area(ax + dx, ay + dy, 1, h, y_major)) return false;  // ends inside: no exit
  // Clip t in [0, 1] to the closed diamond: s_u u + s_v v <= h for the four sign pairs.
  Frac t0{0, 1}, t1{1, 1};
  bool on_upper_edge = false;
  for (int su : {-1, 1})
    for (int sv : {-1, 1}) {
      const i128 p = su * dx + sv * dy, q = h - (su * ax + sv * ay);
      if (p == 0) {
        if (q < 0) return false;              // parallel and outside
        if (q == 0 && sv < 0) on_upper_edge = true;  // runs along an upper edge line
        continue;
      }
      const Frac t = (p > 0) ? Frac{q, p} : Frac{-q, -p};
      if (p > 0 && less(t, t1)) t1 = t;
      if (p < 0 && less(t0, t)) t0 = t;
    }
  if (less(t1, t0)) return false;  // misses the diamond
  if (less(t0, t1)) return !on_upper_edge;  // a piece of positive length: interior or a lower edge
  // Touches at one point: is it in the area?
  return in_area(ax * t0.den + dx * t0.num, ay * t0.den + dy * t0.num, t0.den, h, y_major);
}

int64_t bresenham_midpoint_ties(int64_t d_major, int64_t d_minor) {
  if (d_major == 0) return 0;
  const int64_t g = std::gcd(d_major, d_minor);
  return ((d_major / g) % 2 == 0) ? g : 0;
}

}  // namespace rastsim
