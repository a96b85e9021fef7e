// SPDX-License-Identifier: Apache-2.0
#include "aa/exact_coverage.h"

#include <algorithm>
#include <vector>

namespace rastsim {

namespace {

struct Pt {
  mpq_class x, y;
};
using Poly = std::vector<Pt>;

// Keeps the part of `in` where sign * (coordinate `axis` - bound) >= 0 (Sutherland-Hodgman
// against one axis-aligned line), exactly.
void clip_axis(const Poly& in, Poly& out, int axis, const mpq_class& bound, int sign) {
  out.clear();
  const size_t n = in.size();
  if (n == 0) return;
  auto coord = [axis](const Pt& p) -> const mpq_class& { return axis == 0 ? p.x : p.y; };
  auto side = [&](const Pt& p) { return sign * sgn(coord(p) - bound); };
  bool all_in = true;
  for (const Pt& p : in) all_in = all_in && side(p) >= 0;
  if (all_in) {
    out = in;
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    const Pt& p = in[i];
    const Pt& q = in[(i + 1) % n];
    const int sp = side(p), sq = side(q);
    if (sp >= 0) out.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      // The crossing of p -> q with the line coordinate = bound.
      const mpq_class t = (bound - coord(p)) / (coord(q) - coord(p));
      Pt r;
      if (axis == 0) {
        r.x = bound;
        r.y = p.y + t * (q.y - p.y);
      } else {
        r.y = bound;
        r.x = p.x + t * (q.x - p.x);
      }
      out.push_back(std::move(r));
    }
  }
}

mpq_class shoelace_area(const Poly& p) {
  mpq_class twice = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Pt& a = p[i];
    const Pt& b = p[(i + 1) % p.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return abs(twice) / 2;
}

mpq_class mpq_of(int64_t v) {
  mpz_class z;
  mpz_set_si(z.get_mpz_t(), static_cast<long>(v));
  return mpq_class(z);
}

int64_t floor_shift(int64_t v, int f) { return v >> f; }      // arithmetic: floor(v / 2^f)
int64_t ceil_shift(int64_t v, int f) { return -((-v) >> f); }  // ceil(v / 2^f)

}  // namespace

mpq_class exact_square_area(const std::array<int64_t, 3>& x, const std::array<int64_t, 3>& y, int64_t x0,
                            int64_t y0, int64_t side) {
  Poly a(3), b;
  for (size_t i = 0; i < 3; ++i) a[i] = {mpq_of(x[i]), mpq_of(y[i])};
  const mpq_class lo_x = mpq_of(x0), hi_x = mpq_of(x0 + side), lo_y = mpq_of(y0), hi_y = mpq_of(y0 + side);
  clip_axis(a, b, 0, lo_x, +1);
  clip_axis(b, a, 0, hi_x, -1);
  clip_axis(a, b, 1, lo_y, +1);
  clip_axis(b, a, 1, hi_y, -1);
  if (a.size() < 3) return 0;
  return shoelace_area(a);
}

mpq_class exact_pixel_coverage(const SetupTriangle& t, int px, int py, int frac_bits) {
  const int64_t side = int64_t{1} << frac_bits;
  const int64_t x0 = (int64_t(px) - t.origin_x) << frac_bits, y0 = (int64_t(py) - t.origin_y) << frac_bits;
  mpq_class c = exact_square_area(t.x, t.y, x0, y0, side);
  c /= mpq_of(side) * mpq_of(side);
  return c;
}

SquareClass classify_pixel_square(const SetupTriangle& t, int px, int py, int frac_bits) {
  const int64_t side = int64_t{1} << frac_bits;
  const int64_t x0 = (int64_t(px) - t.origin_x) << frac_bits, y0 = (int64_t(py) - t.origin_y) << frac_bits;
  bool inside = true;
  for (const EdgeEq& e : t.edge) {
    const i128 e00 = e.eval(x0, y0);
    const i128 lo = e00 + i128(std::min<int64_t>(e.a, 0)) * side + i128(std::min<int64_t>(e.b, 0)) * side;
    const i128 hi = e00 + i128(std::max<int64_t>(e.a, 0)) * side + i128(std::max<int64_t>(e.b, 0)) * side;
    if (hi <= 0) return SquareClass::Outside;
    inside = inside && lo >= 0;
  }
  return inside ? SquareClass::Inside : SquareClass::Boundary;
}

PixelRect pixels_under_triangle(const SetupTriangle& t, int frac_bits) {
  const int64_t xmin = std::min({t.x[0], t.x[1], t.x[2]}), xmax = std::max({t.x[0], t.x[1], t.x[2]});
  const int64_t ymin = std::min({t.y[0], t.y[1], t.y[2]}), ymax = std::max({t.y[0], t.y[1], t.y[2]});
  return {int(t.origin_x + floor_shift(xmin, frac_bits)), int(t.origin_y + floor_shift(ymin, frac_bits)),
          int(t.origin_x + ceil_shift(xmax, frac_bits)), int(t.origin_y + ceil_shift(ymax, frac_bits))};
}

}  // namespace rastsim
