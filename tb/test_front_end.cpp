// SPDX-License-Identifier: Apache-2.0
// The geometry front end (ref/front_end.h, docs/clip-space.md): divide by w and viewport
// transform against hand-worked binary32 values, near-plane clipping against exact
// rationals, nothing behind the eye, the guard band, points and lines, and watertight
// closed meshes around the camera (every pixel, and every sample, covered exactly once).
//
// Binary32 expectations were worked out with exact rationals rounded to nearest even
// once an operation (Python fractions); each is derived in the comment above it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/front_end.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "report/stats_json.h"
#include "common/clip_meshes.h"

namespace rastsim {
namespace {

RasterState state(int w, int h) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.viewport_width = w;
  st.fb_height = st.viewport_height = h;
  st.depth_func = DepthFunc::Always;
  return st;
}

ClipVertex cv(float x, float y, float z, float w, uint8_t c = 255) {
  ClipVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.w = w;
  v.r = v.g = v.b = c;
  return v;
}

CmdPrimitives clip_prims(Topology t, std::vector<ClipVertex> v) {
  CmdPrimitives p;
  p.topology = t;
  p.clip_vertices = std::move(v);
  return p;
}

std::vector<ScreenTriangle> run_front_end(const CmdPrimitives& p, const RasterState& st, FrontEndStats& stats) {
  std::vector<ScreenTriangle> out;
  front_end(p, st, SourceLoc{"test", 1}, stats, [&](const ScreenTriangle& t) { out.push_back(t); });
  return out;
}

using testing_common::Coverage;
using testing_common::cube_mesh;
using testing_common::Perspective;
using testing_common::render_coverage;
using testing_common::samples_not_covered_once;
using testing_common::sphere_mesh;

// Divide and viewport by hand. Viewport 64 x 64: W/2 = 32, X + W/2 = 32.
// (1, -1, 0.5, 2): q = 1/2; x_w = (1 * 0.5) * 32 + 32 = 48; y_w = (-0.5) * 32 + 32 = 16;
// z_w = (0.5 * 0.5) * 1 + 0 = 0.25. All exact.
TEST(FrontEnd, DivideAndViewportExact) {
  const RasterState st = state(64, 64);
  SceneVertex s;
  ASSERT_TRUE(to_screen(cv(1, -1, 0.5f, 2), viewport_map(ClipState{}, st), st.color_frac_bits, s));
  EXPECT_EQ(s.x.to_double(), 48.0);
  EXPECT_EQ(s.y.to_double(), 16.0);
  EXPECT_EQ(s.z, 0.25);
  EXPECT_EQ(s.inv_w, 0.5f);
  // viewport_xform 8 4 16 8, depth_range 0.25 0.75: W/2 = 8, X + W/2 = 16, H/2 = 4,
  // Y + H/2 = 8, F - N = 0.5: x_w = 0.5 * 8 + 16 = 20, y_w = -0.5 * 4 + 8 = 6,
  // z_w = 0.25 * 0.5 + 0.25 = 0.375.
  ClipState c;
  c.xform = ViewportXform{false, 8, 4, 16, 8};
  c.depth_near = 0.25f;
  c.depth_far = 0.75f;
  ASSERT_TRUE(to_screen(cv(1, -1, 0.5f, 2), viewport_map(c, st), st.color_frac_bits, s));
  EXPECT_EQ(s.x.to_double(), 20.0);
  EXPECT_EQ(s.y.to_double(), 6.0);
  EXPECT_EQ(s.z, 0.375);
}

// (1, 0, 0, 3) on 64 x 64: q = rn(1/3) = 0x1.555556p-2; x q = q; * 32 = 0x1.555556p+3
// (exact); + 32 = 42.6666674613952637 rounds (ulp 2^-18) to 0x1.555556p+5.
TEST(FrontEnd, DivideRoundsOnceAnOperation) {
  const RasterState st = state(64, 64);
  SceneVertex s;
  ASSERT_TRUE(to_screen(cv(1, 0, 0, 3), viewport_map(ClipState{}, st), st.color_frac_bits, s));
  EXPECT_EQ(s.inv_w, 0x1.555556p-2f);
  EXPECT_EQ(s.x.to_double(), 0x1.555556p+5);
  EXPECT_EQ(s.y.to_double(), 32.0);
}

// No fused multiply-add: with W = 100 (W/2 = 50 = X + W/2), x = -0x1.e24322p-1,
// w = 0x1.46a2cp+0, rounding (x q) * 50 before adding 50 gives 0x1.a2d68p+3; a fused
// (x q) * 50 + 50 would give 0x1.a2d67cp+3 (found by searching random vertices with
// exact rationals).
TEST(FrontEnd, NoFusedMultiplyAdd) {
  const RasterState st = state(100, 100);
  SceneVertex s;
  ASSERT_TRUE(to_screen(cv(-0x1.e24322p-1f, 0, 0, 0x1.46a2cp+0f), viewport_map(ClipState{}, st), st.color_frac_bits, s));
  EXPECT_EQ(s.x.to_double(), 0x1.a2d68p+3);
}

// A triangle crossing the near plane: A = (0, 0, -1, 1) black is behind it (z < 0),
// B = (1, 0, 1, 2), C = (0, 1, 1, 2) white in front. Sutherland-Hodgman over A->B, B->C,
// C->A gives [I_AB, B, C, I_CA]; on A-B (from B, the inside vertex) t = 1 / (1 - -1) =
// 1/2, so I_AB = (1 - 0.5, 0, 0, 2 - 0.5) = (0.5, 0, 0, 1.5), colour 255 - 127.5 =
// 127.5 (binary32, exact); likewise I_CA = (0, 0.5, 0, 1.5). Fanned from I_AB:
// (I_AB, B, C), (I_AB, C, I_CA). On screen the colour is unsigned 8.F: with F = 8 (the
// default interp.color_frac_bits) 127.5 exactly, r = 127 and fraction 128/256; with F =
// 0 (RGB8) 127.5 rounds to nearest even, 128.
TEST(FrontEnd, NearPlaneClipHandWorked) {
  FrontEndStats stats;
  bool clipped = false;
  const auto poly = clip_triangle({cv(0, 0, -1, 1, 0), cv(1, 0, 1, 2), cv(0, 1, 1, 2)}, 1.0f, stats, clipped);
  ASSERT_EQ(poly.size(), 4u);
  EXPECT_TRUE(clipped);
  EXPECT_EQ(stats.clip_vertices_made, 2u);
  const std::array<std::array<float, 4>, 4> want{{{0.5f, 0, 0, 1.5f}, {1, 0, 1, 2}, {0, 1, 1, 2}, {0, 0.5f, 0, 1.5f}}};
  const std::array<float, 4> want_rgb{127.5f, 255, 255, 127.5f};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(poly[i].x, want[i][0]) << i;
    EXPECT_EQ(poly[i].y, want[i][1]) << i;
    EXPECT_EQ(poly[i].z, want[i][2]) << i;
    EXPECT_EQ(poly[i].w, want[i][3]) << i;
    EXPECT_EQ(poly[i].r, want_rgb[i]) << i;
  }
  const RasterState st = state(64, 64);
  FrontEndStats fs;
  const auto tris = run_front_end(clip_prims(Topology::List, {cv(0, 0, -1, 1, 0), cv(1, 0, 1, 2), cv(0, 1, 1, 2)}), st, fs);
  ASSERT_EQ(tris.size(), 2u);
  EXPECT_EQ(fs.triangles_clipped, 1u);
  // I_AB on screen: q = rn(1/1.5) = 0x1.555556p-1, x q = 0x1.555556p-2, * 32 + 32 =
  // 0x1.555556p+5 (as above); B: x_w = 0.5 * 32 + 32 = 48, y_w = 32; depth 0 and 0.5.
  EXPECT_EQ(tris[0][0].x.to_double(), 0x1.555556p+5);
  EXPECT_EQ(tris[0][0].y.to_double(), 32.0);
  EXPECT_EQ(tris[0][0].z, 0.0);
  EXPECT_EQ(tris[0][1].x.to_double(), 48.0);
  EXPECT_EQ(tris[0][1].z, 0.5);
  EXPECT_EQ(tris[1][2].x.to_double(), 32.0);  // I_CA: x = 0
  EXPECT_EQ(tris[1][2].y.to_double(), 0x1.555556p+5);
  ASSERT_EQ(st.color_frac_bits, 8);
  EXPECT_EQ(tris[0][0].r, 127);
  EXPECT_EQ(tris[0][0].rgb_frac, (std::array<uint16_t, 3>{128, 128, 128}));
  EXPECT_EQ(tris[0][1].r, 255);
  EXPECT_EQ(tris[0][1].rgb_frac, (std::array<uint16_t, 3>{0, 0, 0}));
  RasterState rgb8 = st;
  rgb8.color_frac_bits = 0;
  FrontEndStats f8;
  const auto t8 = run_front_end(clip_prims(Topology::List, {cv(0, 0, -1, 1, 0), cv(1, 0, 1, 2), cv(0, 1, 1, 2)}), rgb8, f8);
  ASSERT_EQ(t8.size(), 2u);
  EXPECT_EQ(t8[0][0].r, 128);
  EXPECT_EQ(t8[0][0].rgb_frac, (std::array<uint16_t, 3>{0, 0, 0}));
}

// The llvmpipe comparison's example of a cut triangle (docs/mesa.md, "Found by this
// comparison", item 2; configs/d3d11.toml at 240 x 160, viewport_xform 42 37 153 57):
// pixel (107, 90), 90 LSB from every edge. Its exact colour is the clip-space barycentric
// interpolation of the three input vertices' colours at the pixel centre (b solves
// sum b_k (x_k - nx w_k) = 0, sum b_k (y_k - ny w_k) = 0, sum b_k = 1, in binary64 here,
// as the comparison's oracle does): (22.91, 139.52, 110.47). The new vertices' colours
// carried as unsigned 8.8 give a colour within 1 LSB of it on every channel (rounded to
// RGB8 as each was made, the front end before interp.color_frac_bits, green was 138).
std::array<double, 3> exact_colour(const std::array<ClipVertex, 3>& v, double nx, double ny) {
  // Cramer's rule on the 3 x 3 system above.
  double m[3][3], rhs[3] = {0, 0, 1};
  for (int k = 0; k < 3; ++k) {
    m[0][k] = double(v[size_t(k)].x) - nx * double(v[size_t(k)].w);
    m[1][k] = double(v[size_t(k)].y) - ny * double(v[size_t(k)].w);
    m[2][k] = 1.0;
  }
  const auto det = [](const double (&a)[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  std::array<double, 3> rgb{};
  for (int k = 0; k < 3; ++k) {
    double mk[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) mk[i][j] = j == k ? rhs[i] : m[i][j];
    const double b = det(mk) / d;
    rgb[0] += b * v[size_t(k)].r, rgb[1] += b * v[size_t(k)].g, rgb[2] += b * v[size_t(k)].b;
  }
  return rgb;
}

Fragment cut_triangle_pixel(const std::array<ClipVertex, 3>& v, const RasterState& st, int px, int py) {
  CmdPrimitives p = clip_prims(Topology::List, {v[0], v[1], v[2]});
  p.clip.xform = ViewportXform{false, 42, 37, 153, 57};
  FrontEndStats fs;
  std::vector<Fragment> hits;
  for (const ScreenTriangle& tri : run_front_end(p, st, fs)) {
    SetupTriangle t;
    if (setup_triangle(tri, st, SourceLoc{"test", 1}, t) != SetupOutcome::Accepted) continue;
    const int F = st.coord_format.frac_bits;
    const int64_t sx = t.sample_x(px, F), sy = t.sample_y(py, F);
    if (std::all_of(t.edge.begin(), t.edge.end(), [&](const EdgeEq& e) { return e.eval(sx, sy) + e.bias >= 0; }))
      hits.push_back(interpolate(t, px, py, F));
  }
  EXPECT_EQ(fs.triangles_clipped, 1u);
  EXPECT_EQ(hits.size(), 1u) << "pixel (" << px << ", " << py << ") covered once";
  return hits.empty() ? Fragment{} : hits[0];
}

TEST(FrontEnd, CutTriangleColourWithinOneLsbOfExact) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  cfg.apply_override("display.width=240");
  cfg.apply_override("display.height=160");
  const RasterState st = raster_state_from_config(cfg);
  ASSERT_EQ(st.color_frac_bits, 8);
  const auto c = [](float x, float y, float z, float w, int r, int g, int b) {
    ClipVertex v = cv(x, y, z, w);
    v.r = float(r), v.g = float(g), v.b = float(b);
    return v;
  };
  const std::array<ClipVertex, 3> v{c(-0.218731895f, 0.124569267f, -0.0239124317f, -0.123890437f, 5, 141, 133),
                                    c(-0.0401831307f, 0.000897531165f, -0.00177233375f, -0.0404226892f, 104, 126, 9),
                                    c(6.64543486f, -0.0483763404f, 2.3140626f, 8.76124001f, 46, 184, 78)};
  const int px = 107, py = 90;
  const std::array<double, 3> want =
      exact_colour(v, (px + 0.5 - (42 + 153 / 2.0)) / (153 / 2.0), (py + 0.5 - (37 + 57 / 2.0)) / (57 / 2.0));
  EXPECT_NEAR(want[0], 22.91, 0.005);
  EXPECT_NEAR(want[1], 139.52, 0.005);
  EXPECT_NEAR(want[2], 110.47, 0.005);
  const Fragment f = cut_triangle_pixel(v, st, px, py);
  EXPECT_LE(std::abs(f.r - want[0]), 1.0) << int(f.r);
  EXPECT_LE(std::abs(f.g - want[1]), 1.0) << int(f.g);
  EXPECT_LE(std::abs(f.b - want[2]), 1.0) << int(f.b);
}

// The far plane: A = (0, 0, 3, 2) lies beyond it (w - z = -1), B = (1, 0, 1, 2) and
// C = (0, 1, 1, 2) inside (w - z = 1). On A-B from B: t = 1 / (1 + 1) = 1/2, so
// (1 - 0.5, 0, 1 + 1, 2) = (0.5, 0, 2, 2), on the plane z = w; its depth is 2 * 0.5 = 1.
TEST(FrontEnd, FarPlaneClipHandWorked) {
  const RasterState st = state(64, 64);
  FrontEndStats fs;
  const auto tris = run_front_end(clip_prims(Topology::List, {cv(0, 0, 3, 2), cv(1, 0, 1, 2), cv(0, 1, 1, 2)}), st, fs);
  ASSERT_EQ(tris.size(), 2u);  // [I_AB, B, C, I_CA] fanned
  EXPECT_EQ(fs.clip_vertices_made, 2u);
  EXPECT_EQ(tris[0][0].x.to_double(), 0.5 * 0.5 * 32 + 32);  // x q = 0.25: 40
  EXPECT_EQ(tris[0][0].z, 1.0);
  EXPECT_EQ(tris[0][1].z, 0.5);  // B: 1 * 0.5
}

// A clip-space strip keeps the strip's winding (triangle 1 is (v2, v1, v3)) through the
// front end: both triangles of a quad strip face the same way on screen.
TEST(FrontEnd, StripKeepsItsWinding) {
  const RasterState st = state(64, 64);
  FrontEndStats fs;
  const auto tris = run_front_end(
      clip_prims(Topology::Strip, {cv(-0.5f, -0.5f, 0.5f, 1), cv(0.5f, -0.5f, 0.5f, 1), cv(-0.5f, 0.5f, 0.5f, 1),
                                   cv(0.5f, 0.5f, 0.5f, 1)}),
      st, fs);
  ASSERT_EQ(tris.size(), 2u);
  const auto area2 = [](const ScreenTriangle& t) {
    return (t[1].x.to_double() - t[0].x.to_double()) * (t[2].y.to_double() - t[0].y.to_double()) -
           (t[1].y.to_double() - t[0].y.to_double()) * (t[2].x.to_double() - t[0].x.to_double());
  };
  EXPECT_GT(area2(tris[0]) * area2(tris[1]), 0.0);
  EXPECT_EQ(tris[1][0].x.to_double(), 16.0);  // v2 = (-0.5, 0.5) -> (16, 48)
  EXPECT_EQ(tris[1][0].y.to_double(), 48.0);
}

// A general near crossing against the exact rational intersection (computed in double
// from the binary32 inputs, exact to ~1e-16): every coordinate within 4 binary32 ulps.
TEST(FrontEnd, NearPlaneIntersectionNearExactRational) {
  const ClipVertex in = cv(0.3f, -0.7f, 0.45f, 1.3f), out = cv(-0.9f, 0.2f, -0.8f, 0.35f);
  const ClipVertex got = clip_intersection(in, out, ClipPlane::Near, 1.0f);
  const double t = double(in.z) / (double(in.z) - double(out.z));
  const auto exact = [&](float a, float b) { return double(a) + t * (double(b) - double(a)); };
  const auto ulps = [](float got_v, double want) {
    const float w = float(want);
    return std::fabs(double(got_v) - want) / double(std::nextafter(std::fabs(w), INFINITY) - std::fabs(w));
  };
  EXPECT_LE(ulps(got.x, exact(in.x, out.x)), 4.0);
  EXPECT_LE(ulps(got.y, exact(in.y, out.y)), 4.0);
  EXPECT_LE(ulps(got.w, exact(in.w, out.w)), 4.0);
  EXPECT_EQ(got.z, 0.0f);
  // Interpolated from the inside vertex whichever way the edge runs: bit-identical.
  FrontEndStats s;
  bool c1 = false, c2 = false;
  const auto p1 = clip_triangle({in, out, cv(0, 0, 0.5f, 1)}, 1.0f, s, c1);
  const auto p2 = clip_triangle({out, in, cv(0, 0, 0.5f, 1)}, 1.0f, s, c2);
  const auto has = [&](const std::vector<ClipVertex>& p) {
    return std::any_of(p.begin(), p.end(), [&](const ClipVertex& v) {
      return v.x == got.x && v.y == got.y && v.z == got.z && v.w == got.w;
    });
  };
  EXPECT_TRUE(has(p1));
  EXPECT_TRUE(has(p2));
}

// A shared edge P-Q cut by near and then by the right plane, in two triangles that run
// it in opposite directions: both polygons hold the same vertex where it leaves the
// volume (near's crossing, then the right plane's, each from the inside end).
TEST(FrontEnd, SharedEdgeCutByTwoPlanesIsBitIdentical) {
  const ClipVertex P = cv(0.1f, 0.2f, 0.6f, 1.1f), Q = cv(2.9f, -0.3f, -0.7f, 0.9f);
  const ClipVertex near_cut = clip_intersection(P, Q, ClipPlane::Near, 1.0f);
  ASSERT_LT(plane_distance(near_cut, ClipPlane::Right, 1.0f), 0.0f);  // still outside the right plane
  const ClipVertex want = clip_intersection(P, near_cut, ClipPlane::Right, 1.0f);
  FrontEndStats s;
  bool c = false;
  for (const auto& tri : {std::array{P, Q, cv(-0.5f, 0.6f, 0.5f, 1)}, std::array{Q, P, cv(0.4f, -0.8f, 0.5f, 1)}}) {
    const auto poly = clip_triangle(tri, 1.0f, s, c);
    EXPECT_TRUE(std::any_of(poly.begin(), poly.end(), [&](const ClipVertex& v) {
      return v.x == want.x && v.y == want.y && v.z == want.z && v.w == want.w;
    }));
  }
}

// Behind the eye: w = -1 everywhere, and x/w, y/w, z/w inside the volume, so a divide
// without clipping would draw it. Nothing drawn, counted as behind.
TEST(FrontEnd, BehindTheEyeDrawsNothing) {
  RasterState st = state(64, 64);
  const auto c = render_coverage(
      {clip_prims(Topology::List, {cv(0.5f, 0.5f, -0.5f, -1), cv(-0.5f, 0.5f, -0.5f, -1), cv(0, -0.5f, -0.5f, -1)})},
      st);
  EXPECT_EQ(c.stats.front_end.triangles_behind, 1u);
  EXPECT_EQ(c.stats.traversal.fragments, 0u);
}

// Two vertices behind the eye (z = w - 0.5: a near plane at w = 0.5), one in front:
// A = (0, 0, 0.5, 1), B = (0.5, 0.5, -1.5, -1), C = (-0.5, 0.5, -1.5, -1). On A-B,
// t = 0.5 / (0.5 + 1.5) = 1/4: (0.125, 0.125, 0, 0.5) -> (40, 40) on 64 x 64; on A-C
// (24, 40); A -> (32, 32). Exactly the screen triangle (32,32) (40,40) (24,40) is drawn,
// and nothing above row 32 (a divide without clipping puts B, C at (16, 16), (48, 16)).
TEST(FrontEnd, CrossingTheEyePlaneDrawsOnlyTheFront) {
  const RasterState st = state(64, 64);
  const auto c = render_coverage(
      {clip_prims(Topology::List, {cv(0, 0, 0.5f, 1), cv(0.5f, 0.5f, -1.5f, -1), cv(-0.5f, 0.5f, -1.5f, -1)})}, st);
  CmdPrimitives screen;
  for (auto [x, y] : {std::pair{32, 32}, {40, 40}, {24, 40}}) {
    SceneVertex v;
    v.x = Q64::from_int(x);
    v.y = Q64::from_int(y);
    screen.vertices.push_back(v);
  }
  const auto want = render_coverage({screen}, st);
  EXPECT_EQ(c.count, want.count);
  EXPECT_GT(want.stats.traversal.fragments, 0u);
  EXPECT_EQ(c.stats.front_end.triangles_clipped, 1u);
}

// A large triangle (w = 1, every vertex outside the viewport, up to 2.75 viewports out)
// clipped to the viewport (g = 1) and not clipped at all (g = 4: every vertex inside
// the band, and 88 px from the centre still fits s7.16) covers the same pixels. Its
// crossings were chosen (by an exact-rational search) so that every clip t is dyadic:
// the clipped polygon (-1, -1), (-1, 3/4), (5/16, -1) lies exactly on the original
// edges, and snapping cannot tell the two apart.
TEST(FrontEnd, GuardBandSamePixels) {
  const CmdPrimitives p =
      clip_prims(Topology::List, {cv(-1, -1.75f, 0.5f, 1), cv(-2.5f, 2.75f, 0.5f, 1), cv(0.5f, -1.25f, 0.5f, 1)});
  RasterState st = state(64, 64);
  st.guard_band = 1.0f;
  const auto clipped = render_coverage({p}, st);
  st.guard_band = 4.0f;
  const auto whole = render_coverage({p}, st);
  EXPECT_EQ(clipped.stats.front_end.triangles_clipped, 1u);
  EXPECT_EQ(whole.stats.front_end.triangles_clipped, 0u);
  EXPECT_GT(clipped.stats.traversal.fragments, 1000u);
  EXPECT_EQ(clipped.count, whole.count);
}

TEST(FrontEnd, TriviallyRejectedOutsideOnePlane) {
  FrontEndStats s;
  EXPECT_TRUE(run_front_end(clip_prims(Topology::List, {cv(2, 0, 0.5f, 1), cv(3, 1, 0.5f, 1), cv(2, 1, 0.5f, 1)}),
                            state(64, 64), s)
                  .empty());
  EXPECT_EQ(s.triangles_culled_outside, 1u);
  EXPECT_EQ(s.triangles_clipped, 0u);
}

// A point of size 3 centred on pixel (10, 10)'s centre (x = (10.5 - 32) / 32 =
// -0.671875, exact): the square [9, 12] x [9, 12] covers pixels 9..11 each way; with
// point_sprite, s and t run 0..1 from the top-left corner.
TEST(FrontEnd, PointIsASquare) {
  CmdPrimitives p = clip_prims(Topology::Points, {cv(-0.671875f, -0.671875f, 0.5f, 1)});
  p.clip.point_size = 3;
  p.clip.point_sprite = true;
  const RasterState st = state(64, 64);
  FrontEndStats fs;
  const auto tris = run_front_end(p, st, fs);
  ASSERT_EQ(tris.size(), 2u);
  EXPECT_EQ(tris[0][0].x.to_double(), 9.0);  // top-left
  EXPECT_EQ(tris[0][0].y.to_double(), 9.0);
  EXPECT_EQ(tris[0][0].s, 0.0f);
  EXPECT_EQ(tris[0][0].t, 0.0f);
  EXPECT_EQ(tris[0][2].x.to_double(), 12.0);  // bottom-right
  EXPECT_EQ(tris[0][2].s, 1.0f);
  EXPECT_EQ(tris[0][2].t, 1.0f);
  const auto c = render_coverage({p}, st);
  std::set<std::pair<int, int>> got;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (c.count[size_t(y * 64 + x)] > 0) {
        EXPECT_EQ(c.count[size_t(y * 64 + x)], 1);
        got.insert({x, y});
      }
  std::set<std::pair<int, int>> want;
  for (int y = 9; y < 12; ++y)
    for (int x = 9; x < 12; ++x) want.insert({x, y});
  EXPECT_EQ(got, want);
  // Behind the eye and beyond far: culled.
  FrontEndStats s2;
  EXPECT_TRUE(run_front_end(clip_prims(Topology::Points, {cv(0, 0, 0.5f, -1), cv(0, 0, 2, 1)}), st, s2).empty());
  EXPECT_EQ(s2.points_culled, 2u);
}

// Lines, 1 px wide: (2.5, 5.5) -> (10.5, 5.5) is x-major, the quad [2.5, 10.5] x [5, 6]:
// pixels 2..9 of row 5 (left edge in, right edge out: the top-left rule). The
// transposed line is y-major: column 5, rows 2..9. A line loop of the two ends draws
// the segment twice.
TEST(FrontEnd, LinesAreOnePixelQuads) {
  const auto ndc = [](double px) { return float((px - 32) / 32); };
  const RasterState st = state(64, 64);
  const auto pixels = [&](const CmdPrimitives& p) {
    const auto c = render_coverage({p}, st);
    std::map<std::pair<int, int>, int> m;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        if (int n = c.count[size_t(y * 64 + x)]) m[{x, y}] = n;
    return m;
  };
  std::map<std::pair<int, int>, int> row, col;
  for (int i = 2; i < 10; ++i) {
    row[{i, 5}] = 1;
    col[{5, i}] = 1;
  }
  EXPECT_EQ(pixels(clip_prims(Topology::Lines, {cv(ndc(2.5), ndc(5.5), 0.5f, 1), cv(ndc(10.5), ndc(5.5), 0.5f, 1)})), row);
  EXPECT_EQ(pixels(clip_prims(Topology::Lines, {cv(ndc(5.5), ndc(2.5), 0.5f, 1), cv(ndc(5.5), ndc(10.5), 0.5f, 1)})), col);
  for (auto& [k, n] : row) n = 2;
  EXPECT_EQ(pixels(clip_prims(Topology::LineLoop, {cv(ndc(2.5), ndc(5.5), 0.5f, 1), cv(ndc(10.5), ndc(5.5), 0.5f, 1)})), row);
  // A line from in front of the eye to behind it is clipped at near, not dropped.
  FrontEndStats s;
  EXPECT_EQ(run_front_end(clip_prims(Topology::Lines, {cv(0, 0, 0.5f, 1), cv(0.5f, 0, -1.5f, -1)}), st, s).size(), 2u);
  EXPECT_EQ(s.lines_clipped, 1u);
}

// ---- Watertight closed meshes around the camera ----

void expect_covered_once(const CmdPrimitives& mesh, int samples, float guard_band) {
  RasterState st = state(96, 64);
  st.samples = samples;
  st.guard_band = guard_band;
  const auto c = render_coverage({mesh}, st);
  EXPECT_EQ(samples_not_covered_once(c), 0u) << "of " << c.count.size() << " samples";
  // Some faces are cut by the near plane and some lie behind the eye.
  EXPECT_GT(c.stats.front_end.triangles_clipped, 0u);
  EXPECT_GT(c.stats.front_end.triangles_behind, 0u);
  EXPECT_GT(c.stats.front_end.clip_vertices_made, 0u);
}

TEST(FrontEnd, WatertightCubeAroundTheCamera) {
  const Perspective P(100, 0.05, 10);
  for (int samples : {1, 2, 4, 8, 16})  // every sample count (sample_pattern.h)
    for (float g : {1.0f, 2.0f}) {
      SCOPED_TRACE("samples " + std::to_string(samples) + " guard band " + std::to_string(g));
      expect_covered_once(cube_mesh(P, 5), samples, g);
    }
}

TEST(FrontEnd, WatertightSphereAroundTheCamera) {
  const Perspective P(90, 0.05, 10);
  for (int samples : {1, 2, 4, 8, 16}) {
    SCOPED_TRACE("samples " + std::to_string(samples));
    expect_covered_once(sphere_mesh(P, 24, 40), samples, 1.0f);
  }
}

// A near plane that cuts the cube itself: the eye 0.2 from the nearest face and a near
// distance of 0.5 opens the cube, so the pixels the cut leaves bare are covered 0 times
// and none twice.
TEST(FrontEnd, NearPlaneCutCubeNeverOverlaps) {
  const Perspective P(100, 0.5, 10);
  RasterState st = state(96, 64);
  const auto c = render_coverage({cube_mesh(P, 5)}, st);
  EXPECT_EQ(std::count_if(c.count.begin(), c.count.end(), [](int n) { return n > 1; }), 0);
  EXPECT_GT(c.stats.front_end.triangles_clipped, 0u);
}

// The front end (simulate, estimate and fit draw through it) leaves homogeneous triangles
// to the reference renderer (ref/homogeneous.h) and says so.
TEST(FrontEnd, HomogeneousIsAClearError) {
  RasterState st = state(64, 64);
  st.clip_method = ClipMethod::Homogeneous;
  FrontEndStats s;
  try {
    run_front_end(clip_prims(Topology::List, {cv(0, 0, 0.5f, 1), cv(1, 0, 0.5f, 1), cv(0, 1, 0.5f, 1)}), st, s);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("test:1: clip.method = homogeneous is modelled at the reference level only (rastsim render)"), std::string::npos)
        << e.what();
  }
}

TEST(FrontEnd, NonFiniteInputIsAnError) {
  FrontEndStats s;
  EXPECT_THROW(run_front_end(clip_prims(Topology::List, {cv(INFINITY, 0, 0.5f, 1), cv(1, 0, 0.5f, 1), cv(0, 1, 0.5f, 1)}),
                             state(64, 64), s),
               SceneError);
}

TEST(FrontEnd, OtherLevelsRejectClipSpace) {
  const CmdPrimitives p = clip_prims(Topology::List, {cv(0, 0, 0.5f, 1), cv(1, 0, 0.5f, 1), cv(0, 1, 0.5f, 1)});
  try {
    reject_clip_space(p, SourceLoc{"a.trace", 7});
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("a.trace:7: clip-space primitives (tri4, v4) are not modelled at this level yet", 0), 0u)
        << e.what();
  }
  EXPECT_NO_THROW(reject_clip_space(CmdPrimitives{}, SourceLoc{"a.trace", 7}));
}

// The stats JSON has the front end's keys when a clip-space primitive was drawn, and
// only then (a screen-space scene's stats are unchanged); the threaded render counts the same.
TEST(FrontEnd, StatsJsonAndThreads) {
  const Perspective P(100, 0.05, 10);
  RasterState st = state(96, 64);
  Scene scene;
  scene.commands.push_back(Command{cube_mesh(P, 8), SourceLoc{"test", 1}});
  RenderStats one, four;
  render_scene(scene, st, one);
  render_scene(scene, st, four, {}, Framebuffer::kDefaultTileLog2, 4);
  EXPECT_EQ(one.framebuffer_crc32, four.framebuffer_crc32);
  auto j1 = to_json(one), j4 = to_json(four);
  j1.erase("wall_seconds");
  j4.erase("wall_seconds");
  EXPECT_EQ(j1, j4);
  for (const char* key : {"triangles_clipped", "triangles_behind", "clip_vertices_made", "clip_triangles_in"})
    EXPECT_TRUE(j1.contains(key)) << key;
  EXPECT_EQ(j1["clip_triangles_in"], 6 * 8 * 8 * 2);
  EXPECT_FALSE(to_json(RenderStats{}).contains("triangles_clipped"));
  // The summary line says what the front end did before setup's counts.
  const std::string summary = triangles_summary(one);
  EXPECT_EQ(summary.rfind("768 clip-space triangles (" + std::to_string(one.front_end.triangles_clipped) + " clipped, ", 0), 0u)
      << summary;
  EXPECT_EQ(triangles_summary(RenderStats{}), "0 triangles");
}

}  // namespace
}  // namespace rastsim
