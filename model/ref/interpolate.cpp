// SPDX-License-Identifier: Apache-2.0
#include "ref/interpolate.h"

#include <algorithm>
#include <cmath>

namespace rastsim {

namespace {

// The nearest float to num / den (den > 0): through long double (64-bit mantissa), whose
// rounding before the one to float can matter only within 2^-40 of a float tie.
float nearest_float(i128 num, i128 den) {
  return static_cast<float>(static_cast<long double>(num) / static_cast<long double>(den));
}

using interp_detail::clamp_attr;
using interp_detail::make_fragment;

// Fixed point: v0 and s in units of 2^-D of the attribute LSB, each rounded to nearest
// (ties to even); |num0| < 2^(2N+2+bits) <= 2^88 and D <= 32, so the shifted numerators
// stay below 2^121. Integer additions are exact: after k of them the value is v0 + k s.
struct FixedSpan {
  i128 v0, s;
  FixedSpan(i128 num0, i128 dnum, i128 den, int frac_bits)
      : v0(div_round(num0 << frac_bits, den, Rounding::NearestEven)),
        s(div_round(dnum << frac_bits, den, Rounding::NearestEven)) {}
  uint32_t at(int64_t k, int frac_bits, int bits) const {
    return clamp_attr(shift_right_round(v0 + i128(k) * s, frac_bits, Rounding::HalfUp), bits);
  }
};

// Walks a span from step 0 to step n, calling emit(k, value) for each: the one
// definition of the DDA's arithmetic (see the header).
template <class Emit>
void walk_span(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int bits, Emit&& emit) {
  if (arith == InterpArith::Fixed) {
    const FixedSpan f(num0, dnum, den, frac_bits);
    for (int64_t k = 0; k <= n; ++k) emit(k, f.at(k, frac_bits, bits));
    return;
  }
  const float s = nearest_float(dnum, den);
  float v = nearest_float(num0, den);
  for (int64_t k = 0;; ++k) {
    // floor(v + 1/2) in double: exact for |v| < 2^52.
    emit(k, clamp_attr(static_cast<i128>(std::floor(static_cast<double>(v) + 0.5)), bits));
    if (k == n) break;
    v = v + s;  // one single-precision addition, rounded
  }
}

}  // namespace

uint32_t dda_span_value(i128 num0, i128 dnum, i128 den, int64_t k, InterpArith arith, int frac_bits, int bits) {
  if (arith == InterpArith::Fixed) return FixedSpan(num0, dnum, den, frac_bits).at(k, frac_bits, bits);  // O(1)
  uint32_t out = 0;
  walk_span(num0, dnum, den, k, arith, frac_bits, bits, [&](int64_t i, uint32_t v) { if (i == k) out = v; });
  return out;
}

void dda_span_values(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int bits,
                     std::vector<uint32_t>& out) {
  out.assign(size_t(n + 1), 0);
  walk_span(num0, dnum, den, n, arith, frac_bits, bits, [&](int64_t k, uint32_t v) { out[size_t(k)] = v; });
}

Fragment interpolate_plane_at(const SetupTriangle& t, int px, int py, int64_t sx, int64_t sy) {
  if (t.edges64) {
    // The 64-bit path: the same weights and rational, when every numerator fits int64
    // (tri_setup.h w64_limit); the i128 path below otherwise.
    const int64_t w[3] = {t.edge[1].eval64(sx, sy), t.edge[2].eval64(sx, sy), t.edge[0].eval64(sx, sy)};
    const int64_t lim = t.w64_limit;
    if (w[0] <= lim && w[0] >= -lim && w[1] <= lim && w[1] >= -lim && w[2] <= lim && w[2] >= -lim) {
      const int64_t den = static_cast<int64_t>(t.area2);  // < 2^(2N+2) <= 2^62 with edges64
      return make_fragment(t, px, py, [&](uint32_t a0, uint32_t a1, uint32_t a2, int bits) {
        const int64_t num = w[0] * int64_t(a0) + w[1] * int64_t(a1) + w[2] * int64_t(a2);
        return clamp_attr(div_round_in<int64_t>(num, den, Rounding::HalfUp), bits);
      });
    }
  }
  // Weight of vertex k is the edge opposite it: edge (k+1)%3 runs between the other two.
  const i128 w[3] = {t.edge[1].eval(sx, sy), t.edge[2].eval(sx, sy), t.edge[0].eval(sx, sy)};
  return make_fragment(t, px, py, [&](uint32_t a0, uint32_t a1, uint32_t a2, int bits) {
    const i128 num = w[0] * a0 + w[1] * a1 + w[2] * a2;
    return clamp_attr(div_round(num, t.area2, Rounding::HalfUp), bits);
  });
}

PlaneStepper::PlaneStepper(const SetupTriangle& t, int frac_bits) : t_(&t), frac_bits_(frac_bits) {
  if (t.samples != 1 || !t.edges64 || t.area2 > t.w64_limit) return;
  den_ = static_cast<int64_t>(t.area2);
  int i = 0;
  bool fits = true;
  make_fragment(t, 0, 0, [&](uint32_t a0, uint32_t a1, uint32_t a2, int) {
    a_[i][0] = a0, a_[i][1] = a1, a_[i][2] = a2;
    if (a0 == a1 && a1 == a2) {
      q_[i] = a0;  // flat (see the header): dq_, dr_, r_ stay 0
    } else {
      var_[nvar_++] = i;
      // x-step of num (weight k is edge (k+1)%3), exact; then its floor quotient and remainder.
      const i128 d = (i128(t.edge[1].a) * a0 + i128(t.edge[2].a) * a1 + i128(t.edge[0].a) * a2) << frac_bits;
      fits = fits && fits_signed(d, 63);
      const i128 q = div_round(d, t.area2, Rounding::Floor);
      dq_[i] = static_cast<int64_t>(q);
      dr_[i] = static_cast<int64_t>(d - q * t.area2);
    }
    ++i;
    return 0u;
  });
  active_ = fits;
}

void PlaneStepper::restart(int px, int py) {
  const SetupTriangle& t = *t_;
  const int64_t sx = t.sample_x(px, frac_bits_), sy = t.sample_y(py, frac_bits_);
  const int64_t w[3] = {t.edge[1].eval64(sx, sy), t.edge[2].eval64(sx, sy), t.edge[0].eval64(sx, sy)};
  for (int k = 0; k < nvar_; ++k) {
    const int i = var_[k];
    const int64_t num = w[0] * int64_t(a_[i][0]) + w[1] * int64_t(a_[i][1]) + w[2] * int64_t(a_[i][2]);
    q_[i] = div_round_in<int64_t>(num, den_, Rounding::Floor);
    r_[i] = num - q_[i] * den_;
  }
}

Fragment interpolate_plane(const SetupTriangle& t, int px, int py, int frac_bits) {
  return interpolate_plane_at(t, px, py, t.sample_x(px, frac_bits), t.sample_y(py, frac_bits));
}

Fragment interpolate(const SetupTriangle& t, int px, int py, int frac_bits) {
  if (t.interp_method == InterpMethod::Plane) return interpolate_plane(t, px, py, frac_bits);
  // The span's first pixel: the leftmost covered centre of this row (px itself is covered).
  const int64_t sy = t.sample_y(py, frac_bits);
  int x0 = std::max(t.bbox.x0, 0);
  for (; x0 < px; ++x0) {
    const int64_t sx = t.sample_x(x0, frac_bits);
    bool in = true;
    for (const EdgeEq& e : t.edge) in = in && e.eval(sx, sy) + e.bias >= 0;
    if (in) break;
  }
  const int64_t sx0 = t.sample_x(x0, frac_bits);
  const i128 w[3] = {t.edge[1].eval(sx0, sy), t.edge[2].eval(sx0, sy), t.edge[0].eval(sx0, sy)};
  // d w_k / d x per pixel: the edge's a coefficient times one pixel (2^F raw units).
  const i128 dw[3] = {i128(t.edge[1].a) << frac_bits, i128(t.edge[2].a) << frac_bits, i128(t.edge[0].a) << frac_bits};
  const int64_t k = px - x0;
  return make_fragment(t, px, py, [&](uint32_t a0, uint32_t a1, uint32_t a2, int bits) {
    const i128 num0 = w[0] * a0 + w[1] * a1 + w[2] * a2, dnum = dw[0] * a0 + dw[1] * a1 + dw[2] * a2;
    return dda_span_value(num0, dnum, t.area2, k, t.interp_arith, t.interp_frac_bits, bits);
  });
}

}  // namespace rastsim
