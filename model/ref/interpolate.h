// SPDX-License-Identifier: Apache-2.0
// Attribute interpolation: depth, colour and texture coordinates at a pixel centre from
// barycentric weights.
//
// The weights are the triangle's own edge values at the sample (exact integers in
// raw^2 units, 2F fraction bits): w0 = E1, w1 = E2, w2 = E0, each >= 0 for a covered
// sample, w0 + w1 + w2 = area2. An attribute is
//     attr = round_half_up((w0*a0 + w1*a1 + w2*a2) / area2)
// an exact rational rounded once, so the result lies between the vertex values and is
// the same in every model. Hardware: one divider per attribute with a quotient as wide
// as the attribute (8 bits for colour, raster.depth_bits for depth, the signed
// interp.texcoord_format for s, t); widths in docs/fixed-point.md. This is
// interp.method = "plane", the default, and the whole story for an `affine` triangle.
//
// Perspective-correct (a triangle set up with affine false: interp.perspective and
// different 1/w, tri_setup.h): depth stays the rational above (z/w is linear on
// screen); colour and texture coordinates weight each vertex by its Q_k as well:
//     attr = round_half_up((e0 Q0 a0 + e1 Q1 a1 + e2 Q2 a2) / (e0 Q0 + e1 Q1 + e2 Q2))
// with e_k = w_k. interp.recip = exact divides exactly (the golden); newton multiplies
// by the reciprocal unit's y ~ 1/D (ref/recip.h) from the top 40 bits of D. Widths,
// truncations and the extrapolation rule in docs/clip-space.md.
//
// interp.method = "dda" (the lecture notes' incremental spans): along each row the
// covered pixels form one span; its first pixel x0 gets the exact value v0 (the
// rational above) rounded to the DDA's arithmetic, and the x-step s = d attr / d x
// (exact rational: sum of a_k * 2^F * attr_k over area2) is rounded once to it too;
// pixel x0 + k gets v0 + s + s + ... (k additions in that arithmetic), rounded half up
// to the attribute's integer and clamped to its range [0, 2^bits - 1] (8 bits colour,
// raster.depth_bits depth):
//   - f32: IEEE single (v0 and s rounded to nearest from the exact rational);
//   - fixed: interp.dda_frac_bits fraction bits D below the attribute's LSB (v0 and s
//     rounded to nearest, ties to even; k additions are exact, so v = v0 + k s).
// The span's first pixel is found by testing the row's pixel centres from the bounding
// box's left edge (the same exact edge test as traversal), so the value of a pixel does
// not depend on the order in which traversal delivers it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "ref/sample_pattern.h"
#include "ref/tri_setup.h"

namespace rastsim {

struct Fragment {
  int x = 0, y = 0;        // pixel
  uint32_t z = 0;          // unorm raster.depth_bits
  uint8_t r = 0, g = 0, b = 0;
  uint16_t mask = 1;       // the samples it writes (raster.samples > 1)
  uint8_t samples = 1;     // raster.samples: how many bits of mask are meaningful
  int32_t s = 0, t = 0;    // texture coordinate, raw interp.texcoord_format (signed)
  bool operator==(const Fragment&) const = default;
};

// The fragment at pixel (px, py) by the triangle's interp_method.
Fragment interpolate(const SetupTriangle& t, int px, int py, int frac_bits);
// The same by plane equations, whatever the triangle's method (the exact reference).
Fragment interpolate_plane(const SetupTriangle& t, int px, int py, int frac_bits);
// Plane equations at raw point (sx, sy) for pixel (px, py). Outside the triangle (a
// multisampled pixel whose centre is not covered) the weights go negative and the
// rational is extrapolated; the rounded value is clamped to the attribute's range
// [0, 2^bits - 1] (texture coordinates: the format's range; a no-op inside the triangle).
// Perspective-correct where the denominator D = sum e_k Q_k is <= 0 (only outside the
// triangle) with the negative weights taken as 0.
Fragment interpolate_plane_at(const SetupTriangle& t, int px, int py, int64_t sx, int64_t sy);

// interpolate_plane for the pixels of one single-sample triangle in turn, without a
// division where it can: a pixel just right of the previous one steps each attribute's
// exact quotient and remainder of num / area2 by those of the constant x-step
// sum_k a_k (edge.a << F) (a remainder past area2 carries one), every other pixel is
// divided out as interpolate_plane does. All in int64, so active() only when the
// triangle's edges64 holds, area2 <= w64_limit (the weights of a covered centre lie in
// [0, area2]) and the steps fit int64; the same fragments as interpolate_plane
// (tb/test_int64_paths.cpp). Only for covered pixel centres of an affine triangle.
class PlaneStepper {
 public:
  PlaneStepper(const SetupTriangle& t, int frac_bits);
  bool active() const { return active_; }  // else call interpolate_plane
  // Every attribute flat: at() gives the same depth and colour at every pixel.
  bool flat() const { return nvar_ == 0; }
  // Inline below and always inlined: it runs once a fragment, and a call returns the
  // fragment through memory, which the ROP loop then reads back (a stall behind its stores).
  [[gnu::always_inline]] Fragment at(int px, int py);

 private:
  static constexpr int kAttrs = 6;    // in make_fragment's order: z, r, g, b, s, t
  static constexpr int kTexAttr = 4;  // index of s
  void restart(int px, int py);       // q_, r_ at (px, py) by division
  [[gnu::always_inline]] void step(int i) {
    q_[i] += dq_[i];
    r_[i] += dr_[i];  // both remainders in [0, den): the sum is below 2 den
    if (r_[i] >= den_) {
      r_[i] -= den_;
      ++q_[i];
    }
  }
  const SetupTriangle* t_;          // a pointer, so that a stepper can be copied (PixelShader)
  int frac_bits_;
  bool active_ = false, have_last_ = false;
  int last_x_ = 0, last_y_ = 0;
  int64_t den_ = 1;
  int64_t q_[kAttrs]{}, r_[kAttrs]{}, dq_[kAttrs]{}, dr_[kAttrs]{};
  int64_t a_[kAttrs][3]{};
  // A flat attribute (the same value a at the three vertices) is that value at every
  // point: num = a (w0 + w1 + w2) = a area2 exactly, so q = a, r = 0 and its x-step is 0
  // (sum_k edge.a = 0). Its q_ and r_ are set once and restart() divides only the others
  // (var_[0..nvar_)): a flat-shaded triangle interpolates without a division.
  int nvar_ = 0;
  int var_[kAttrs]{};
  bool tex_varies_ = false;  // s or t is not flat
};

// The fragments of one pixel whose sample coverage mask is m (docs/antialiasing.md):
// - one sample: interpolate() at the centre, mask 1 (any interp.method);
// - msaa: one fragment, plane equations at the pixel centre (extrapolated when the centre
//   is outside), mask m: its colour and depth go to every covered sample;
// - ssaa: one fragment per covered sample s, in sample order, plane equations at the
//   sample's own position, mask 1 << s.
template <class Emit>
void shade_pixel(const SetupTriangle& t, int px, int py, uint32_t m, int frac_bits, Emit&& emit);

// shade_pixel for a run of pixels of one triangle, with PlaneStepper where it applies
// (one sample, plane equations): the reference pipeline and the SystemC interpolator
// shade through it, so both take the same fast path to the same fragments.
class PixelShader {
 public:
  PixelShader(const SetupTriangle& t, int frac_bits)
      : t_(t), frac_bits_(frac_bits), plane_(t, frac_bits),
        stepped_(plane_.active() && t.interp_method == InterpMethod::Plane) {}
  template <class Emit>
  void shade(int px, int py, uint32_t mask, Emit&& emit) {
    if (stepped_) emit(plane_.at(px, py));
    else shade_pixel(t_, px, py, mask, frac_bits_, emit);
  }
  // True when shade() emits exactly one fragment a pixel, at(px, py): one sample, plane
  // equations, PlaneStepper active (the pipeline then shades and writes runs).
  bool stepped() const { return stepped_; }
  // A stepped() shader's fragments of a run of covered pixels x0, x0 + 1, ... of row y:
  // returns use(frag), frag(x) the fragment of pixel (x, y), to be called for x0, x0 + 1,
  // ... in turn. With every attribute flat, frag is the run's first fragment with its x
  // moved along (nothing is stepped, and the loop keeps the fragment in registers);
  // else PlaneStepper steps along the run. The reference's run path hands frag to the
  // ROP (rop_write_run), the SystemC interpolator stores the fragments: one fast path.
  template <class Use>
  [[gnu::always_inline]] decltype(auto) shade_run(int y, int x0, Use&& use) {
    if (plane_.flat()) {
      const Fragment f = plane_.at(x0, y);
      // Built field by field, not copied whole and x changed: a copy through memory with x
      // stored into it stalls the next load of it (store forwarding), a fragment at a time.
      return use([f](int x) { return Fragment{x, f.y, f.z, f.r, f.g, f.b, f.mask, f.samples, f.s, f.t}; });
    }
    return use([this, y](int x) { return plane_.at(x, y); });
  }

 private:
  const SetupTriangle& t_;
  int frac_bits_;
  PlaneStepper plane_;
  bool stepped_;
};

namespace interp_detail {

// v clamped to an attribute's range [lo, hi].
template <class T>
inline int64_t clamp_attr(T v, int64_t lo, int64_t hi) {
  return static_cast<int64_t>(std::clamp<T>(v, T(lo), T(hi)));
}
inline int64_t unorm_max(int bits) { return (int64_t{1} << bits) - 1; }

// round_half_up(num / (den 2^frac)), den > 0: the floor quotient with its frac low bits
// rounded off, floor((floor(num / den) + 2^(frac-1)) / 2^frac), the same value (frac = 0:
// round_half_up(num / den)). A colour of unsigned 8.F vertex values rounds to RGB8 so.
template <class T>
inline T div_round_frac(T num, T den, int frac) {
  if (frac == 0) return div_round_in<T>(num, den, Rounding::HalfUp);
  return (div_round_in<T>(num, den, Rounding::Floor) + (T(1) << (frac - 1))) >> frac;
}

// The fragment at pixel (px, py) whose depth is depth_attr(z0, z1, z2, lo, hi, 0) and whose
// every other attribute is attr(a0, a1, a2, lo, hi, frac) of the three vertex values
// (int64), lo and hi the attribute's range: [0, 2^raster.depth_bits - 1] for depth,
// [0, 255] for colour, interp.texcoord_format's raw range for s and t; frac the fraction
// bits of the vertex values below the result's LSB (the colour's interp.color_frac_bits,
// else 0), which the result rounds off once (round half up).
template <class DepthAttr, class Attr>
[[gnu::always_inline]] inline Fragment make_fragment(const SetupTriangle& t, int px, int py, DepthAttr&& depth_attr,
                                                     Attr&& attr) {
  Fragment f;
  const int cf = t.color_frac_bits;
  f.x = px;
  f.y = py;
  f.z = static_cast<uint32_t>(depth_attr(t.z[0], t.z[1], t.z[2], 0, unorm_max(t.depth_bits), 0));
  f.r = static_cast<uint8_t>(attr(t.rgb[0][0], t.rgb[1][0], t.rgb[2][0], 0, 255, cf));
  f.g = static_cast<uint8_t>(attr(t.rgb[0][1], t.rgb[1][1], t.rgb[2][1], 0, 255, cf));
  f.b = static_cast<uint8_t>(attr(t.rgb[0][2], t.rgb[1][2], t.rgb[2][2], 0, 255, cf));
  f.samples = static_cast<uint8_t>(t.samples);
  f.s = static_cast<int32_t>(attr(t.tex_s[0], t.tex_s[1], t.tex_s[2], t.tex_min, t.tex_max, 0));
  f.t = static_cast<int32_t>(attr(t.tex_t[0], t.tex_t[1], t.tex_t[2], t.tex_min, t.tex_max, 0));
  return f;
}
// Every attribute, depth included, by attr (the affine methods).
template <class Attr>
[[gnu::always_inline]] inline Fragment make_fragment(const SetupTriangle& t, int px, int py, Attr&& attr) {
  return make_fragment(t, px, py, attr, attr);
}

}  // namespace interp_detail

inline Fragment PlaneStepper::at(int px, int py) {
  if (nvar_ == 0) {
    // Every attribute flat: q_ and r_ hold at every point.
  } else if (have_last_ && py == last_y_ && px == last_x_ + 1) {
    // A flat attribute's steps are 0: a no-op. Texture coordinates, flat in every
    // untextured scene, are stepped only when one of them varies.
    for (int i = 0; i < kTexAttr; ++i) step(i);
    if (tex_varies_)
      for (int i = kTexAttr; i < kAttrs; ++i) step(i);
  } else {
    restart(px, py);
  }
  have_last_ = true;
  last_x_ = px;
  last_y_ = py;
  // Round half up from the floor quotient and remainder, as div_round_in does.
  // Colour (frac > 0): the floor quotient's frac bits rounded off (div_round_frac).
  int i = 0;
  return interp_detail::make_fragment(*t_, px, py, [&](int64_t, int64_t, int64_t, int64_t lo, int64_t hi, int frac) __attribute__((always_inline)) {
    const int j = i++;
    if (j >= kTexAttr && !tex_varies_) return q_[j];  // flat s, t: the vertex value (r_ = 0)
    const int64_t v = frac ? (q_[j] + (int64_t{1} << (frac - 1))) >> frac : r_[j] >= den_ - r_[j] ? q_[j] + 1 : q_[j];
    return interp_detail::clamp_attr(v, lo, hi);
  });
}

// One DDA span value: the attribute (bits wide) at step k of a span whose exact start
// value is num0 / den and exact step dnum / den (den > 0), in the given arithmetic.
uint32_t dda_span_value(i128 num0, i128 dnum, i128 den, int64_t k, InterpArith arith, int frac_bits, int bits);
// The values at steps 0..n of the same span, walked once (the stability search on ramps,
// tb/stability/test_interp_dda.cpp): out[k] == dda_span_value(..., k, ...).
void dda_span_values(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int bits,
                     std::vector<uint32_t>& out);

template <class Emit>
void shade_pixel(const SetupTriangle& t, int px, int py, uint32_t m, int frac_bits, Emit&& emit) {
  if (t.samples == 1) {
    emit(interpolate(t, px, py, frac_bits));
    return;
  }
  const int64_t cx = t.sample_x(px, frac_bits), cy = t.sample_y(py, frac_bits);
  if (t.aa_mode == AaMode::Msaa) {
    Fragment f = interpolate_plane_at(t, px, py, cx, cy);
    f.mask = static_cast<uint16_t>(m);
    emit(f);
    return;
  }
  const SamplePattern& p = sample_pattern(t.samples, frac_bits);
  for (int s = 0; s < t.samples; ++s) {
    if (!((m >> s) & 1)) continue;
    Fragment f = interpolate_plane_at(t, px, py, cx + p.dx[size_t(s)], cy + p.dy[size_t(s)]);
    f.mask = static_cast<uint16_t>(1u << s);
    emit(f);
  }
}

}  // namespace rastsim
