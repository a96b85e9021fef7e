// SPDX-License-Identifier: Apache-2.0
#include "ref/tri_setup.h"

#include "ref/sample_pattern.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

namespace rastsim {

const char* to_string(SetupOutcome o) {
  switch (o) {
    case SetupOutcome::Accepted: return "accepted";
    case SetupOutcome::CulledZeroArea: return "zero_area";
    case SetupOutcome::CulledBackFace: return "back_face";
    case SetupOutcome::CulledFrontFace: return "front_face";
    case SetupOutcome::CulledOutOfRange: return "out_of_range";
    case SetupOutcome::CulledOutsideClip: return "outside_clip";
  }
  return "?";
}

// Fill-rule bias for an edge already oriented so that the interior is E > 0.
// Direct3D 11 top-left rule: a sample exactly on an edge is covered when the edge is a
// left edge (interior to its right: a > 0) or a top edge (horizontal, interior below:
// a == 0 && b > 0, y grows downward). bottom_right mirrors it.
int fill_bias(const EdgeEq& e, FillRule rule) {
  switch (rule) {
    case FillRule::TopLeft: return (e.a > 0 || (e.a == 0 && e.b > 0)) ? 0 : -1;
    case FillRule::BottomRight: return (e.a < 0 || (e.a == 0 && e.b < 0)) ? 0 : -1;
    case FillRule::Inclusive: return 0;
    case FillRule::Exclusive: return -1;
  }
  return -1;
}

// A texture coordinate (repeats) in raw interp.texcoord_format units: v 2^F rounded to
// nearest even (exact in double: v is binary32); nullopt outside the format or not finite.
std::optional<int32_t> quantize_texcoord(float v, const FixedFormat& fmt) {
  if (v == 0.0f) return 0;  // every untextured vertex: the common case, without the conversions
  const double scaled = double(v) * double(fmt.one());  // exact: a 24-bit significand times 2^F
  if (!(std::abs(scaled) < 0x1p40)) return std::nullopt;  // not finite, or far outside any format
  // Ties to even by the binary64 addition of 1.5 2^52 (exact below 2^51 in magnitude;
  // the default rounding mode), cheaper than a library nearbyint.
  const double raw = (scaled + 0x1.8p52) - 0x1.8p52;
  if (raw < double(fmt.raw_min()) || raw > double(fmt.raw_max())) return std::nullopt;
  return static_cast<int32_t>(raw);
}

// Smallest pixel index whose centre (p + 1/2, in raw units relative to origin) is >= raw.
int64_t first_pixel_at_or_after(int64_t raw, int64_t origin, int frac_bits) {
  const i128 t = i128(raw) - (i128(1) << (frac_bits - 1));
  // ceil(t / 2^F) = -floor(-t / 2^F)
  return origin - static_cast<int64_t>(shift_right_round(-t, frac_bits, Rounding::Floor));
}
// Largest pixel index whose centre is <= raw.
int64_t last_pixel_at_or_before(int64_t raw, int64_t origin, int frac_bits) {
  const i128 t = i128(raw) - (i128(1) << (frac_bits - 1));
  return origin + static_cast<int64_t>(shift_right_round(t, frac_bits, Rounding::Floor));
}

namespace {

// The raster state a set-up triangle carries to traversal and interpolation.
void take_raster_state(const RasterState& st, SetupTriangle& t) {
  t.origin_x = st.origin_x();
  t.origin_y = st.origin_y();
  t.interp_method = st.interp_method;
  t.interp_arith = st.interp_arith;
  t.interp_frac_bits = st.interp_frac_bits;
  t.depth_bits = st.depth_bits;
  t.samples = st.samples;
  t.aa_mode = st.aa_mode;
  t.edges64 = edges_fit_int64(st.coord_format);
  t.tex_min = st.texcoord_format.raw_min();
  t.tex_max = st.texcoord_format.raw_max();
  t.recip = st.recip;
  t.recip_seed_bits = st.recip_seed_bits;
  t.recip_iterations = st.recip_iterations;
}

std::string vertex_where(const SourceLoc& loc, int i) { return loc.str() + ": vertex " + std::to_string(i); }

// Texture coordinates and 1/w checked and quantised (the general path of take_attributes).
void take_texture_and_w(const std::array<SceneVertex, 3>& v, const RasterState& st, const SourceLoc& loc,
                        SetupTriangle& t, int64_t& attr_max) {
  const FixedFormat& f = st.texcoord_format;
  for (int i = 0; i < 3; ++i) {
    const auto s = quantize_texcoord(v[i].s, f), tt = quantize_texcoord(v[i].t, f);
    if (!s || !tt)
      throw SceneError(vertex_where(loc, i) + " texture coordinate (" + std::to_string(v[i].s) + ", " +
                       std::to_string(v[i].t) + ") is outside interp.texcoord_format " + f.name() + ": [" +
                       std::to_string(f.to_double(f.raw_min())) + ", " + std::to_string(f.to_double(f.raw_max())) +
                       "] repeats");
    t.tex_s[i] = *s;
    t.tex_t[i] = *tt;
    attr_max = std::max({attr_max, int64_t(std::abs(int64_t(*s))), int64_t(std::abs(int64_t(*tt)))});
    if (!(std::isfinite(v[i].inv_w) && v[i].inv_w > 0.0f))
      throw SceneError(vertex_where(loc, i) + " 1/w " + std::to_string(v[i].inv_w) + " is not finite and > 0");
  }
}

// Depth, colour, texture coordinates and perspective weights of the three vertices, and
// the 64-bit interpolation limit that follows from the largest attribute magnitude.
void take_attributes(const std::array<SceneVertex, 3>& v, const RasterState& st, const SourceLoc& loc,
                     SetupTriangle& t) {
  for (int i = 0; i < 3; ++i) {
    const auto z = quantize_unorm(v[i].z, st.depth_bits);
    if (!z) throw SceneError(vertex_where(loc, i) + " depth " + std::to_string(v[i].z) + " is outside [0, 1]");
    t.z[i] = *z;
    const int F = st.color_frac_bits;
    t.rgb[i] = {uint32_t(v[i].r) << F | v[i].rgb_frac[0], uint32_t(v[i].g) << F | v[i].rgb_frac[1],
                uint32_t(v[i].b) << F | v[i].rgb_frac[2]};
  }
  t.color_frac_bits = st.color_frac_bits;
  int64_t attr_max = int64_t((uint64_t{1} << std::max(8 + st.color_frac_bits, st.depth_bits)) - 1);
  const float w0 = v[0].inv_w;
  const bool same_w = w0 == v[1].inv_w && w0 == v[2].inv_w;
  const bool untextured = v[0].s == 0.0f && v[1].s == 0.0f && v[2].s == 0.0f && v[0].t == 0.0f &&
                          v[1].t == 0.0f && v[2].t == 0.0f;
  if (untextured && same_w && std::isfinite(w0) && w0 > 0.0f) {  // every screen-space triangle
    t.tex_s = t.tex_t = {0, 0, 0};
  } else {
    take_texture_and_w(v, st, loc, t, attr_max);
  }
  t.w64_limit = INT64_MAX / (3 * attr_max);
  // Equal 1/w give equal Q_k: affine, no weights needed.
  t.persp_q = same_w || !st.perspective ? std::array<uint32_t, 3>{1, 1, 1}
                                        : perspective_weights({v[0].inv_w, v[1].inv_w, v[2].inv_w});
  t.affine = t.persp_q[0] == t.persp_q[1] && t.persp_q[1] == t.persp_q[2];
  if (!t.affine && st.interp_method == InterpMethod::Dda)
    throw SceneError(loc.str() + ": interp.method = \"dda\" interpolates affinely only and this triangle's vertices "
                     "have different 1/w; set interp.method = \"plane\" or interp.perspective = false");
}

}  // namespace

std::array<uint32_t, 3> perspective_weights(const std::array<float, 3>& inv_w) {
  std::array<int, 3> e{};
  std::array<int64_t, 3> m{};
  for (size_t k = 0; k < 3; ++k) {
    // 1/w = f 2^e, f in [1/2, 1): the 24-bit significand is f 2^24 (exact, subnormals too).
    m[k] = static_cast<int64_t>(std::ldexp(std::frexp(double(inv_w[k]), &e[k]), 24));
  }
  const int emax = std::max({e[0], e[1], e[2]});
  std::array<uint32_t, 3> q{};
  for (size_t k = 0; k < 3; ++k) {
    const int shift = std::min(emax - e[k], 30);  // beyond 25 bits every value rounds to 0
    q[k] = static_cast<uint32_t>(std::max<i128>(1, shift_right_round(m[k], shift, Rounding::NearestEven)));
  }
  return q;
}

SetupOutcome setup_triangle(const std::array<SceneVertex, 3>& v, const RasterState& st,
                            const SourceLoc& loc, SetupTriangle& t) {
  const FixedFormat& fmt = st.coord_format;
  take_raster_state(st, t);
  for (int i = 0; i < 3; ++i) {
    const auto sx = snap_coord(v[i].x, t.origin_x, fmt);
    const auto sy = snap_coord(v[i].y, t.origin_y, fmt);
    if (!sx || !sy) {
      if (st.out_of_range == OutOfRange::Cull) return SetupOutcome::CulledOutOfRange;
      const double lo = fmt.to_double(fmt.raw_min()), hi = fmt.to_double(fmt.raw_max());
      throw SceneError(loc.str() + ": vertex " + std::to_string(i) + " (" +
                       std::to_string(v[i].x.to_double()) + ", " + std::to_string(v[i].y.to_double()) +
                       ") is outside the " + fmt.name() + " coordinate range: x in [" +
                       std::to_string(t.origin_x + lo) + ", " + std::to_string(t.origin_x + hi) +
                       "], y in [" + std::to_string(t.origin_y + lo) + ", " +
                       std::to_string(t.origin_y + hi) +
                       "] px (set raster.out_of_range = \"cull\" to drop such triangles)");
    }
    t.x[i] = *sx;
    t.y[i] = *sy;
  }

  // Attributes first, so a bad depth is reported even for a culled triangle.
  take_attributes(v, st, loc, t);

  // Doubled signed area, exact: > 0 means clockwise on screen (y grows downward).
  t.area2 = i128(t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - i128(t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
  if (t.area2 == 0) return SetupOutcome::CulledZeroArea;
  t.ccw_on_screen = t.area2 < 0;
  const bool front = t.ccw_on_screen == st.front_ccw;
  if (st.cull == CullMode::Back && !front) return SetupOutcome::CulledBackFace;
  if (st.cull == CullMode::Front && front) return SetupOutcome::CulledFrontFace;

  // Edge i from vertex i to i+1: E = a*x + b*y + c with a = y_i - y_{i+1},
  // b = x_{i+1} - x_i, c = -(a*x_i + b*y_i); E > 0 inside a clockwise triangle.
  const int sign = t.area2 > 0 ? 1 : -1;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    EdgeEq& e = t.edge[i];
    e.a = sign * (t.y[i] - t.y[j]);
    e.b = sign * (t.x[j] - t.x[i]);
    e.c = -(i128(e.a) * t.x[i] + i128(e.b) * t.y[i]);
    e.bias = fill_bias(e, st.fill_rule);
  }
  if (sign < 0) t.area2 = -t.area2;

  // Bounding box of pixel centres inside the snapped vertices' hull, clipped. A pixel
  // whose sample s sits at centre + d_s is in the box when some sample may be, so the
  // hull is widened by the pattern's offset box (0 for one sample).
  const int F = fmt.frac_bits;
  const SamplePattern& pat = sample_pattern(st.samples, F);
  const int64_t xmin = std::min({t.x[0], t.x[1], t.x[2]}) - pat.dx_max;
  const int64_t xmax = std::max({t.x[0], t.x[1], t.x[2]}) - pat.dx_min;
  const int64_t ymin = std::min({t.y[0], t.y[1], t.y[2]}) - pat.dy_max;
  const int64_t ymax = std::max({t.y[0], t.y[1], t.y[2]}) - pat.dy_min;
  const PixelRect clip = st.clip_rect();
  const int64_t bx0 = std::max<int64_t>(first_pixel_at_or_after(xmin, t.origin_x, F), clip.x0);
  const int64_t by0 = std::max<int64_t>(first_pixel_at_or_after(ymin, t.origin_y, F), clip.y0);
  const int64_t bx1 = std::min<int64_t>(last_pixel_at_or_before(xmax, t.origin_x, F) + 1, clip.x1);
  const int64_t by1 = std::min<int64_t>(last_pixel_at_or_before(ymax, t.origin_y, F) + 1, clip.y1);
  if (bx0 >= bx1 || by0 >= by1) return SetupOutcome::CulledOutsideClip;
  t.bbox = {int(bx0), int(by0), int(bx1), int(by1)};

  return SetupOutcome::Accepted;
}

}  // namespace rastsim
