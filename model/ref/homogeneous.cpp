// SPDX-License-Identifier: Apache-2.0
#include "ref/homogeneous.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "ref/prim_assembly.h"
#include "ref/recip.h"
#include "ref/sample_pattern.h"

namespace rastsim {

int homogeneous_depth_shift(const ViewportMap& m, int frac_bits) {
  int s = 0;
  while (s < kMaxFormatBits - frac_bits && std::ldexp(1.0, s) < std::max({double(m.half_w), double(m.half_h), 1.0}))
    ++s;
  return s;
}

HomogeneousVertex homogeneous_vertex(const ClipVertex& c, const ViewportMap& m, int64_t origin_x, int64_t origin_y,
                                     int depth_shift) {
  // Binary64: each product is exact (a 24-bit significand times a half-integer below
  // 2^28), so x~ and y~ are the exact sums rounded once to nearest even; z~ = z 2^s is
  // exact. z~ is as large as x~ and y~ of a point in the view volume, so the block keeps
  // as many bits of z/w as of x/w.
  const double cx = double(m.centre_x) - double(origin_x), cy = double(m.centre_y) - double(origin_y);
  const double v[4] = {double(c.x) * double(m.half_w) + cx * double(c.w),
                       double(c.y) * double(m.half_h) + cy * double(c.w),
                       std::ldexp(double(c.z), depth_shift), double(c.w)};
  int e = INT_MIN;  // the block exponent: every |v| < 2^e
  for (double d : v) {
    if (d == 0.0) continue;
    int ed = 0;
    std::frexp(d, &ed);
    e = std::max(e, ed);
  }
  HomogeneousVertex h;
  if (e == INT_MIN) return h;  // the vertex (0, 0, 0, 0)
  // v 2^(30 - e), |.| < 2^30, rounded to nearest even (the default rounding mode): |V| <= 2^30.
  for (size_t i = 0; i < 4; ++i) h.v[i] = static_cast<int64_t>(std::nearbyint(std::ldexp(v[i], kHomogeneousBits - e)));
  h.exp = e - kHomogeneousBits;
  return h;
}

bool HomogeneousTriangle::covers(int64_t x, int64_t y) const {
  for (const SampleFunc& f : edge)
    if (f.eval(x, y) + f.bias < 0) return false;
  return near_test.eval(x, y) >= 0 && far_test.eval(x, y) >= 0;
}

namespace {

constexpr int kX = 0, kY = 1, kZ = 2, kW = 3;

// Bit length of |v| (0 for 0).
int bit_length(i128 v) {
  const u128 m = v < 0 ? u128(-v) : u128(v);
  const auto hi = static_cast<uint64_t>(m >> 64), lo = static_cast<uint64_t>(m);
  return hi ? 128 - __builtin_clzll(hi) : lo ? 64 - __builtin_clzll(lo) : 0;
}

// The edge functions, oriented, and the determinant (> 0 after orientation; 0: degenerate).
i128 build_edges(const std::array<HomogeneousVertex, 3>& h, const RasterState& st, int depth_shift,
                 HomogeneousTriangle& t) {
  const int F = st.coord_format.frac_bits;
  for (int m = 0; m < 3; ++m) {
    const auto& p = h[size_t(m)].v;
    const auto& q = h[size_t((m + 1) % 3)].v;
    SampleFunc& e = t.edge[size_t(m)];
    // det[s, P, Q] of the sample s = (x, y, 1) in pixels, rows x~, y~, w: |a|, |b|, |c| <= 2^61.
    e.a = i128(p[kY]) * q[kW] - i128(p[kW]) * q[kY];
    e.b = i128(p[kW]) * q[kX] - i128(p[kX]) * q[kW];
    e.c = (i128(p[kX]) * q[kY] - i128(p[kY]) * q[kX]) << F;  // raw sample units: E' = 2^F E
  }
  // det = sum_k lambda_k W_k at any point; at the origin lambda_k = c of edge (k+1)%3.
  i128 det = 0;
  for (int k = 0; k < 3; ++k) det += (t.edge[size_t((k + 1) % 3)].c >> F) * h[size_t(k)].v[kW];
  t.ccw_on_screen = det < 0;  // det = w0 w1 w2 area2 when every w > 0: > 0 is clockwise (y down)
  if (det < 0) {
    for (SampleFunc& e : t.edge) e.a = -e.a, e.b = -e.b, e.c = -e.c;
    det = -det;
  }
  for (SampleFunc& e : t.edge)
    e.bias = fill_bias(EdgeEq{static_cast<int64_t>(e.a), static_cast<int64_t>(e.b), e.c, 0}, st.fill_rule);
  // n = sum_k E_{(k+1)%3} Z_k = 2^(F+s) det z/w; far: 2^(F+s) det - n. |n| < 2^126 for
  // I + F <= 31, and F + s <= 31 keeps 2^(F+s) det below 2^124.
  SampleFunc n;
  for (int k = 0; k < 3; ++k) {
    const SampleFunc& e = t.edge[size_t((k + 1) % 3)];
    const int64_t z = h[size_t(k)].v[kZ];
    n.a += e.a * z;
    n.b += e.b * z;
    n.c += e.c * z;
  }
  t.near_test = n;
  t.depth_den = det << (F + depth_shift);
  t.far_test = SampleFunc{-n.a, -n.b, t.depth_den - n.c, 0};
  return det;
}

// The pixels a covered sample may lie in: the viewport and scissor, the viewport_xform
// rectangle (the clip method clips x and y at +-w there), and, when every W > 0, the box
// of the vertices' screen positions X 2^F / W (floor / ceil, raw), widened by the sample
// pattern as setup widens a box. A triangle with a vertex at or behind w = 0 has no
// bounded screen box: its region is the rest.
PixelRect homogeneous_region(const std::array<HomogeneousVertex, 3>& h, const ClipState& clip, const RasterState& st,
                             const HomogeneousTriangle& t) {
  PixelRect r = st.clip_rect();
  const ViewportXform& x = clip.xform;
  if (!x.whole_viewport) r = r.intersect({x.x, x.y, x.x + x.width, x.y + x.height});
  if (!std::all_of(h.begin(), h.end(), [](const HomogeneousVertex& v) { return v.v[kW] > 0; }) || r.empty()) return r;
  const int F = t.frac_bits;
  const SamplePattern& pat = sample_pattern(t.samples, F);
  const auto range = [&](int axis, int64_t origin, int64_t d_min, int64_t d_max, int lo, int hi) {
    i128 mn = 0, mx = 0;
    for (size_t k = 0; k < 3; ++k) {
      const i128 num = i128(h[k].v[size_t(axis)]) << F;  // below 2^61 in magnitude
      const i128 f = div_round(num, h[k].v[kW], Rounding::Floor), c = -div_round(-num, h[k].v[kW], Rounding::Floor);
      mn = k == 0 ? f : std::min(mn, f);
      mx = k == 0 ? c : std::max(mx, c);
    }
    const int64_t a = first_pixel_at_or_after(int64_t(mn) - d_max, origin, F);
    const int64_t b = last_pixel_at_or_before(int64_t(mx) - d_min, origin, F) + 1;
    return std::pair<int, int>{int(std::clamp<int64_t>(a, lo, hi)), int(std::clamp<int64_t>(b, lo, hi))};
  };
  const auto [x0, x1] = range(kX, t.origin_x, pat.dx_min, pat.dx_max, r.x0, r.x1);
  const auto [y0, y1] = range(kY, t.origin_y, pat.dy_min, pat.dy_max, r.y0, r.y1);
  return {x0, y0, x1, y1};
}

// Colour, texture coordinates, depth range and the interpolation state.
void take_attributes(const std::array<ClipVertex, 3>& v, const ClipState& clip, const RasterState& st,
                     const SourceLoc& loc, HomogeneousTriangle& t) {
  const FixedFormat& f = st.texcoord_format;
  for (size_t k = 0; k < 3; ++k) {
    t.rgb[k] = {uint8_t(v[k].r), uint8_t(v[k].g), uint8_t(v[k].b)};  // an input vertex's RGB8, exact in binary32
    const auto s = quantize_texcoord(v[k].s, f), tt = quantize_texcoord(v[k].t, f);
    if (!s || !tt)
      throw SceneError(loc.str() + ": vertex " + std::to_string(k) + " texture coordinate (" + std::to_string(v[k].s) +
                       ", " + std::to_string(v[k].t) + ") is outside interp.texcoord_format " + f.name());
    t.tex_s[k] = *s;
    t.tex_t[k] = *tt;
  }
  t.tex_min = f.raw_min();
  t.tex_max = f.raw_max();
  const auto lo = quantize_unorm(clip.depth_near, st.depth_bits), hi = quantize_unorm(clip.depth_far, st.depth_bits);
  if (!lo || !hi) throw SceneError(loc.str() + ": depth_range is outside [0, 1]");
  t.depth_lo = *lo;
  t.depth_hi = *hi;
  t.perspective = st.perspective;
  t.recip = st.recip;
  t.recip_seed_bits = st.recip_seed_bits;
  t.recip_iterations = st.recip_iterations;
  t.frac_bits = st.coord_format.frac_bits;
  t.samples = st.samples;
  t.depth_bits = st.depth_bits;
  t.aa_mode = st.aa_mode;
  t.origin_x = st.origin_x();
  t.origin_y = st.origin_y();
}

// floor(m v / d) as q and the remainder r, for 0 <= v <= d < 2^126 and m < 2^32, one bit
// of m at a time (the product would need 160 bits).
void mul_div(uint32_t m, i128 v, i128 d, i128& q, i128& r) {
  q = r = 0;
  for (int bit = 31; bit >= 0; --bit) {
    q <<= 1;
    r <<= 1;
    if (r >= d) r -= d, ++q;
    if ((m >> bit) & 1) {
      r += v;
      if (r >= d) r -= d, ++q;
    }
  }
}

// Depth at n = sum E_k Z_k: round_half_up((lo (D - n) + hi n) / D), D = 2^(F+s) det and n
// clamped to [0, D] (z/w in [0, 1]; only an extrapolated centre is outside).
uint32_t depth_at(const HomogeneousTriangle& t, i128 n) {
  const i128 D = t.depth_den;
  n = std::clamp<i128>(n, 0, D);
  i128 q1, r1, q2, r2;
  mul_div(t.depth_lo, D - n, D, q1, r1);
  mul_div(t.depth_hi, n, D, q2, r2);
  i128 q = q1 + q2, r = r1 + r2;
  if (r >= D) r -= D, ++q;
  return static_cast<uint32_t>(r >= D - r ? q + 1 : q);
}

constexpr int kWeightBits = 63;  // aligned weights: signed, |omega| < 2^62

// omega_k = floor(v_k 2^(shift_k - s)), s chosen so that the largest is kWeightBits wide.
std::array<i128, 3> align_weights(const std::array<i128, 3>& v, const std::array<int, 3>& shift) {
  int top = INT_MIN;
  for (size_t k = 0; k < 3; ++k)
    if (v[k] != 0) top = std::max(top, bit_length(v[k]) + 1 + shift[k]);
  std::array<i128, 3> w{};
  if (top == INT_MIN) return w;
  for (size_t k = 0; k < 3; ++k) {
    const int s = shift[k] + kWeightBits - top;  // <= kWeightBits - width(v_k)
    w[k] = s >= 0 ? v[k] << s : s <= -127 ? (v[k] < 0 ? -1 : 0) : v[k] >> -s;
  }
  return w;
}

}  // namespace

SetupOutcome setup_homogeneous(const std::array<ClipVertex, 3>& v, const ClipState& clip, const RasterState& st,
                               const SourceLoc& loc, HomogeneousTriangle& t) {
  take_attributes(v, clip, st, loc, t);
  const ViewportMap map = viewport_map(clip, st);
  std::array<HomogeneousVertex, 3> h;
  const int depth_shift = homogeneous_depth_shift(map, t.frac_bits);
  for (size_t k = 0; k < 3; ++k) h[k] = homogeneous_vertex(v[k], map, t.origin_x, t.origin_y, depth_shift);
  int emax = INT_MIN;
  for (size_t k = 0; k < 3; ++k) {
    t.w[k] = h[k].v[kW];
    emax = std::max(emax, h[k].exp);
  }
  for (size_t k = 0; k < 3; ++k) t.weight_shift[k] = emax - h[k].exp;
  if (build_edges(h, st, depth_shift, t) == 0) return SetupOutcome::CulledZeroArea;
  const bool front = t.ccw_on_screen == st.front_ccw;
  if (st.cull == CullMode::Back && !front) return SetupOutcome::CulledBackFace;
  if (st.cull == CullMode::Front && front) return SetupOutcome::CulledFrontFace;
  t.region = homogeneous_region(h, clip, st, t);
  return t.region.empty() ? SetupOutcome::CulledOutsideClip : SetupOutcome::Accepted;
}

Fragment homogeneous_fragment(const HomogeneousTriangle& t, int px, int py, int64_t x, int64_t y) {
  std::array<i128, 3> e{};  // vertex k's edge value
  for (size_t k = 0; k < 3; ++k) e[k] = t.edge[(k + 1) % 3].eval(x, y);
  Fragment f;
  f.x = px;
  f.y = py;
  f.samples = static_cast<uint8_t>(t.samples);
  f.z = depth_at(t, t.near_test.eval(x, y));
  // Perspective: lambda_k ~ E_k 2^(exp_max - exp_k); affine (interp.perspective = false):
  // the screen barycentrics ~ E_k W_k (their sum is 2^F det everywhere).
  std::array<i128, 3> w = t.perspective ? align_weights(e, t.weight_shift)
                                        : align_weights({e[0] * t.w[0], e[1] * t.w[1], e[2] * t.w[2]}, {0, 0, 0});
  i128 den = w[0] + w[1] + w[2];
  if (den <= 0) {  // only an extrapolated pixel centre (msaa): negative weights taken as 0
    for (i128& wk : w) wk = std::max<i128>(wk, 0);
    den = w[0] + w[1] + w[2];
    if (den == 0) {  // a centre behind the eye: the vertices' mean
      w = {1, 1, 1};
      den = 3;
    }
  }
  const bool newton = t.recip == RecipMethod::Newton;
  const NewtonDivider div = newton ? NewtonDivider(den, t.recip_seed_bits, t.recip_iterations) : NewtonDivider{};
  const auto attr = [&](int64_t a0, int64_t a1, int64_t a2, int64_t lo, int64_t hi) {
    const i128 num = w[0] * a0 + w[1] * a1 + w[2] * a2;
    return static_cast<int64_t>(
        std::clamp<i128>(newton ? div.quotient(num) : div_round(num, den, Rounding::HalfUp), lo, hi));
  };
  f.r = static_cast<uint8_t>(attr(t.rgb[0][0], t.rgb[1][0], t.rgb[2][0], 0, 255));
  f.g = static_cast<uint8_t>(attr(t.rgb[0][1], t.rgb[1][1], t.rgb[2][1], 0, 255));
  f.b = static_cast<uint8_t>(attr(t.rgb[0][2], t.rgb[1][2], t.rgb[2][2], 0, 255));
  f.s = static_cast<int32_t>(attr(t.tex_s[0], t.tex_s[1], t.tex_s[2], t.tex_min, t.tex_max));
  f.t = static_cast<int32_t>(attr(t.tex_t[0], t.tex_t[1], t.tex_t[2], t.tex_min, t.tex_max));
  return f;
}

namespace {

// Early-out / early-in of the raw sample box [x0, x1] x [y0, y1]: a linear function's
// extremes over a box are at its corners.
TileClass classify(const HomogeneousTriangle& t, int64_t x0, int64_t x1, int64_t y0, int64_t y1) {
  bool all_in = true;
  const auto test = [&](const SampleFunc& f) {
    const i128 hi = f.a * (f.a >= 0 ? x1 : x0) + f.b * (f.b >= 0 ? y1 : y0) + f.c;
    const i128 lo = f.a * (f.a >= 0 ? x0 : x1) + f.b * (f.b >= 0 ? y0 : y1) + f.c;
    all_in = all_in && lo + f.bias >= 0;
    return hi + f.bias >= 0;
  };
  for (const SampleFunc& f : {t.edge[0], t.edge[1], t.edge[2], t.near_test, t.far_test})
    if (!test(f)) return TileClass::Rejected;
  return all_in ? TileClass::Accepted : TileClass::Partial;
}

// The fragments of pixel (px, py) whose coverage mask is m (ref/interpolate.h shade_pixel's rule).
void shade(const HomogeneousTriangle& t, const SamplePattern& pat, int px, int py, uint32_t m,
           const std::function<void(const Fragment&)>& emit) {
  const int64_t cx = t.sample_x(px), cy = t.sample_y(py);
  if (t.samples == 1 || t.aa_mode == AaMode::Msaa) {
    Fragment f = homogeneous_fragment(t, px, py, cx, cy);
    f.mask = static_cast<uint16_t>(t.samples == 1 ? 1u : m);
    emit(f);
    return;
  }
  for (int s = 0; s < t.samples; ++s) {
    if (!((m >> s) & 1)) continue;
    Fragment f = homogeneous_fragment(t, px, py, cx + pat.dx[size_t(s)], cy + pat.dy[size_t(s)]);
    f.mask = static_cast<uint16_t>(1u << s);
    emit(f);
  }
}

}  // namespace

void rasterize_homogeneous(const HomogeneousTriangle& t, int tile_size, TraversalCounters& c,
                           const std::function<void(const Fragment&)>& emit) {
  const SamplePattern& pat = sample_pattern(t.samples, t.frac_bits);
  const uint32_t full = full_sample_mask(t.samples);
  const PixelRect tiles = tile_range(t.region, tile_size);
  for (int ty = tiles.y0; ty < tiles.y1; ++ty)
    for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
      const PixelRect fp = tile_footprint(t.region, tile_size, tx, ty);
      ++c.tiles_visited;
      const TileClass cls = classify(t, t.sample_x(fp.x0) + pat.dx_min, t.sample_x(fp.x1 - 1) + pat.dx_max,
                                     t.sample_y(fp.y0) + pat.dy_min, t.sample_y(fp.y1 - 1) + pat.dy_max);
      if (cls == TileClass::Rejected) {
        ++c.tiles_rejected;
        continue;
      }
      const bool accepted = cls == TileClass::Accepted;
      if (accepted) {
        ++c.tiles_accepted;
        c.count_accepted(fp.area(), t.samples);
      } else {
        ++c.tiles_partial;
        c.count_tests(uint64_t(fp.area()), t.samples);
      }
      for (int py = fp.y0; py < fp.y1; ++py)
        for (int px = fp.x0; px < fp.x1; ++px) {
          uint32_t m = full;
          if (!accepted) {
            m = 0;
            for (int s = 0; s < t.samples; ++s)
              if (t.covers(t.sample_x(px) + pat.dx[size_t(s)], t.sample_y(py) + pat.dy[size_t(s)])) m |= 1u << s;
            if (m == 0) continue;
            c.count_pixel(m, t.samples);
          }
          shade(t, pat, px, py, m, emit);
        }
    }
}

bool draws_homogeneous(const CmdPrimitives& p, const RasterState& st) {
  return p.clip_space() && st.clip_method == ClipMethod::Homogeneous && triangle_count(p.topology, 3) > 0;
}

void draw_homogeneous(const CmdPrimitives& p, const RasterState& st, const SourceLoc& loc, FrontEndStats& fe,
                      TraversalCounters& c, const std::function<bool(SetupOutcome)>& setup_done,
                      const std::function<void(const Fragment&)>& emit) {
  check_clip_space_finite(p, loc);
  const auto& cv = p.clip_vertices;
  for (size_t k = 0; k < triangle_count(p.topology, cv.size()); ++k) {
    const auto i = triangle_indices(p.topology, k);
    const std::array<ClipVertex, 3> v{cv[i[0]], cv[i[1]], cv[i[2]]};
    ++fe.clip_triangles_in;
    if (std::all_of(v.begin(), v.end(), [](const ClipVertex& a) { return a.w <= 0.0f; })) {
      ++fe.triangles_behind;
      continue;
    }
    // Outside one plane of the view volume at every vertex (exact comparisons): so is
    // every point of the triangle, whatever the signs of w.
    const auto outside = [&](auto out) { return std::all_of(v.begin(), v.end(), out); };
    if (outside([](const ClipVertex& a) { return a.z < 0.0f; }) || outside([](const ClipVertex& a) { return a.z > a.w; }) ||
        outside([](const ClipVertex& a) { return a.x < -a.w; }) || outside([](const ClipVertex& a) { return a.x > a.w; }) ||
        outside([](const ClipVertex& a) { return a.y < -a.w; }) || outside([](const ClipVertex& a) { return a.y > a.w; })) {
      ++fe.triangles_culled_outside;
      continue;
    }
    ++fe.clip_triangles_out;
    HomogeneousTriangle t;
    if (!setup_done(setup_homogeneous(v, p.clip, st, loc, t))) continue;
    rasterize_homogeneous(t, st.tile_size, c, emit);
  }
}

}  // namespace rastsim
