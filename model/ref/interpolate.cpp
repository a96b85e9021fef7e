// SPDX-License-Identifier: Apache-2.0
#include "ref/interpolate.h"

#include "ref/recip.h"

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
using interp_detail::div_round_frac;
using interp_detail::make_fragment;
using interp_detail::unorm_max;

// Fixed point: v0 and s in units of 2^-D of the attribute LSB, each rounded to nearest
// (ties to even); |num0| < 2^(2N+2+bits) <= 2^88 and D <= 32, so the shifted numerators
// stay below 2^121. Integer additions are exact: after k of them the value is v0 + k s.
struct FixedSpan {
  i128 v0, s;
  FixedSpan(i128 num0, i128 dnum, i128 den, int frac_bits)
      : v0(div_round(num0 << frac_bits, den, Rounding::NearestEven)),
        s(div_round(dnum << frac_bits, den, Rounding::NearestEven)) {}
  int64_t at(int64_t k, int frac_bits, int64_t lo, int64_t hi) const {
    return clamp_attr(shift_right_round(v0 + i128(k) * s, frac_bits, Rounding::HalfUp), lo, hi);
  }
};

// Walks a span from step 0 to step n, calling emit(k, value) for each: the one
// definition of the DDA's arithmetic (see the header); values clamped to [lo, hi].
template <class Emit>
void walk_span(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int64_t lo, int64_t hi,
               Emit&& emit) {
  if (arith == InterpArith::Fixed) {
    const FixedSpan f(num0, dnum, den, frac_bits);
    for (int64_t k = 0; k <= n; ++k) emit(k, f.at(k, frac_bits, lo, hi));
    return;
  }
  const float s = nearest_float(dnum, den);
  float v = nearest_float(num0, den);
  for (int64_t k = 0;; ++k) {
    // floor(v + 1/2) in double: exact for |v| < 2^52.
    emit(k, clamp_attr(static_cast<i128>(std::floor(static_cast<double>(v) + 0.5)), lo, hi));
    if (k == n) break;
    v = v + s;  // one single-precision addition, rounded
  }
}

// dda_span_value of an attribute whose range is [lo, hi].
int64_t dda_span_value_in(i128 num0, i128 dnum, i128 den, int64_t k, InterpArith arith, int frac_bits, int64_t lo,
                          int64_t hi) {
  if (arith == InterpArith::Fixed) return FixedSpan(num0, dnum, den, frac_bits).at(k, frac_bits, lo, hi);  // O(1)
  int64_t out = 0;
  walk_span(num0, dnum, den, k, arith, frac_bits, lo, hi, [&](int64_t i, int64_t v) { if (i == k) out = v; });
  return out;
}

// Perspective-correct colour and texture coordinates from the weights w (see the header);
// depth affine, the same rational as interpolate_plane_at's.
Fragment interpolate_perspective(const SetupTriangle& t, int px, int py, const i128 (&w)[3]) {
  i128 e[3], den = 0;
  for (int k = 0; k < 3; ++k) den += e[k] = w[k] * t.persp_q[size_t(k)];
  if (den <= 0) {  // only outside the triangle (sum_k w_k = area2 > 0): negative weights to 0
    den = 0;
    for (int k = 0; k < 3; ++k) den += e[k] = std::max<i128>(w[k], 0) * t.persp_q[size_t(k)];
  }
  const bool newton = t.recip == RecipMethod::Newton;
  const NewtonDivider div = newton ? NewtonDivider(den, t.recip_seed_bits, t.recip_iterations) : NewtonDivider{};
  const auto depth = [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi, int) {
    return clamp_attr(div_round(w[0] * a0 + w[1] * a1 + w[2] * a2, t.area2, Rounding::HalfUp), lo, hi);
  };
  return make_fragment(t, px, py, depth, [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi, int frac) {
    const i128 num = e[0] * a0 + e[1] * a1 + e[2] * a2;
    return clamp_attr(newton ? div.quotient(num, frac) : div_round_frac(num, den, frac), lo, hi);
  });
}

}  // namespace

uint32_t dda_span_value(i128 num0, i128 dnum, i128 den, int64_t k, InterpArith arith, int frac_bits, int bits) {
  return static_cast<uint32_t>(dda_span_value_in(num0, dnum, den, k, arith, frac_bits, 0, unorm_max(bits)));
}

void dda_span_values(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int bits,
                     std::vector<uint32_t>& out) {
  out.assign(size_t(n + 1), 0);
  walk_span(num0, dnum, den, n, arith, frac_bits, 0, unorm_max(bits),
            [&](int64_t k, int64_t v) { out[size_t(k)] = static_cast<uint32_t>(v); });
}

Fragment interpolate_plane_at(const SetupTriangle& t, int px, int py, int64_t sx, int64_t sy) {
  if (!t.affine) {
    const i128 w[3] = {t.edge[1].eval(sx, sy), t.edge[2].eval(sx, sy), t.edge[0].eval(sx, sy)};
    return interpolate_perspective(t, px, py, w);
  }
  if (t.edges64) {
    // The 64-bit path: the same weights and rational, when every numerator fits int64
    // (tri_setup.h w64_limit); the i128 path below otherwise.
    const int64_t w[3] = {t.edge[1].eval64(sx, sy), t.edge[2].eval64(sx, sy), t.edge[0].eval64(sx, sy)};
    const int64_t lim = t.w64_limit;
    if (w[0] <= lim && w[0] >= -lim && w[1] <= lim && w[1] >= -lim && w[2] <= lim && w[2] >= -lim) {
      const int64_t den = static_cast<int64_t>(t.area2);  // < 2^(2N+2) <= 2^62 with edges64
      return make_fragment(t, px, py, [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi, int frac) {
        // A flat attribute is its vertex value (num = a area2 exactly: the weights sum to
        // area2 at every point), without a division: untextured scenes' s, t.
        if (a0 == a1 && a1 == a2) return frac ? (a0 + (int64_t{1} << (frac - 1))) >> frac : a0;
        const int64_t num = w[0] * a0 + w[1] * a1 + w[2] * a2;
        return clamp_attr(div_round_frac<int64_t>(num, den, frac), lo, hi);
      });
    }
  }
  // Weight of vertex k is the edge opposite it: edge (k+1)%3 runs between the other two.
  const i128 w[3] = {t.edge[1].eval(sx, sy), t.edge[2].eval(sx, sy), t.edge[0].eval(sx, sy)};
  return make_fragment(t, px, py, [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi, int frac) {
    const i128 num = w[0] * a0 + w[1] * a1 + w[2] * a2;
    return clamp_attr(div_round_frac(num, t.area2, frac), lo, hi);
  });
}

PlaneStepper::PlaneStepper(const SetupTriangle& t, int frac_bits) : t_(&t), frac_bits_(frac_bits) {
  if (t.samples != 1 || !t.affine || !t.edges64 || t.area2 > t.w64_limit) return;
  den_ = static_cast<int64_t>(t.area2);
  int i = 0;
  bool fits = true;
  make_fragment(t, 0, 0, [&](int64_t a0, int64_t a1, int64_t a2, int64_t, int64_t, int) {
    a_[i][0] = a0, a_[i][1] = a1, a_[i][2] = a2;
    if (a0 == a1 && a1 == a2) {
      q_[i] = a0;  // flat (see the header): dq_, dr_, r_ stay 0
    } else {
      var_[nvar_++] = i;
      tex_varies_ = tex_varies_ || i >= kTexAttr;
      // x-step of num (weight k is edge (k+1)%3), exact; then its floor quotient and remainder.
      const i128 d = (i128(t.edge[1].a) * a0 + i128(t.edge[2].a) * a1 + i128(t.edge[0].a) * a2) << frac_bits;
      fits = fits && fits_signed(d, 63);
      const i128 q = div_round(d, t.area2, Rounding::Floor);
      dq_[i] = static_cast<int64_t>(q);
      dr_[i] = static_cast<int64_t>(d - q * t.area2);
    }
    ++i;
    return int64_t{0};
  });
  active_ = fits;
}

void PlaneStepper::restart(int px, int py) {
  const SetupTriangle& t = *t_;
  const int64_t sx = t.sample_x(px, frac_bits_), sy = t.sample_y(py, frac_bits_);
  const int64_t w[3] = {t.edge[1].eval64(sx, sy), t.edge[2].eval64(sx, sy), t.edge[0].eval64(sx, sy)};
  for (int k = 0; k < nvar_; ++k) {
    const int i = var_[k];
    const int64_t num = w[0] * a_[i][0] + w[1] * a_[i][1] + w[2] * a_[i][2];
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
  // A colour of 8.F vertex values: the same span over area2 2^F (the rational of the colour).
  return make_fragment(t, px, py, [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi, int frac) {
    const i128 num0 = w[0] * a0 + w[1] * a1 + w[2] * a2, dnum = dw[0] * a0 + dw[1] * a1 + dw[2] * a2;
    return dda_span_value_in(num0, dnum, t.area2 << frac, k, t.interp_arith, t.interp_frac_bits, lo, hi);
  });
}

}  // namespace rastsim
