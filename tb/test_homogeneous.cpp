// SPDX-License-Identifier: Apache-2.0
// 2D-homogeneous rasterization (clip.method = "homogeneous", ref/homogeneous.h,
// docs/clip-space.md): closed meshes around the camera are watertight at 1, 2 and 4
// samples; nothing behind the eye is drawn, not even by the sign rule alone; hand-worked
// perspective colour and depth; and against the clip method on thousands of seeded random
// clip-space triangles, every differing sample lies within one coordinate LSB of an edge
// of the exact visible polygon (tb/mesa/clip_geometry.h, in double, independent of both).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "common/clip_meshes.h"
#include "config/raster_state_config.h"
#include "mesa/clip_geometry.h"
#include "mesa/clip_scenes.h"
#include "ref/front_end.h"
#include "ref/homogeneous.h"
#include "ref/pipeline.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"
#include "report/stats_json.h"

namespace rastsim {
namespace {

using testing_common::cube_mesh;
using testing_common::Perspective;
using testing_common::render_coverage;
using testing_common::samples_not_covered_once;
using testing_common::sphere_mesh;

RasterState homogeneous_state(int w, int h) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.viewport_width = w;
  st.fb_height = st.viewport_height = h;
  st.depth_func = DepthFunc::Always;
  st.clip_method = ClipMethod::Homogeneous;
  return st;
}

// A vertex of red r (green and blue 0).
ClipVertex cv(float x, float y, float z, float w, uint8_t r = 255) { return ClipVertex{x, y, z, w, float(r), 0, 0}; }

CmdPrimitives tri(std::vector<ClipVertex> v) {
  CmdPrimitives p;
  p.topology = Topology::List;
  p.clip_vertices = std::move(v);
  return p;
}

void expect_covered_once(const CmdPrimitives& mesh, int samples) {
  RasterState st = homogeneous_state(96, 64);
  st.samples = samples;
  const auto c = render_coverage({mesh}, st);
  EXPECT_EQ(samples_not_covered_once(c), 0u) << "of " << c.count.size() << " samples";
  // No new vertices; some triangles behind the eye; the rest drawn whole.
  EXPECT_GT(c.stats.front_end.triangles_behind, 0u);
  EXPECT_EQ(c.stats.front_end.triangles_clipped, 0u);
  EXPECT_EQ(c.stats.front_end.clip_vertices_made, 0u);
  EXPECT_GT(c.stats.traversal.sample_tests, 0u);
}

TEST(Homogeneous, WatertightCubeAroundTheCamera) {
  for (int samples : {1, 2, 4}) {
    SCOPED_TRACE("samples " + std::to_string(samples));
    expect_covered_once(cube_mesh(Perspective(100, 0.05, 10), 5), samples);
  }
}

TEST(Homogeneous, WatertightSphereAroundTheCamera) {
  for (int samples : {1, 2, 4}) {
    SCOPED_TRACE("samples " + std::to_string(samples));
    expect_covered_once(sphere_mesh(Perspective(90, 0.05, 10), 24, 40), samples);
  }
}

// The near plane cuts the cube open (eye 0.2 from the nearest face, near 0.5): the bare
// pixels are covered 0 times, none twice.
TEST(Homogeneous, NearPlaneCutCubeNeverOverlaps) {
  const auto c = render_coverage({cube_mesh(Perspective(100, 0.5, 10), 5)}, homogeneous_state(96, 64));
  EXPECT_EQ(std::count_if(c.count.begin(), c.count.end(), [](int n) { return n > 1; }), 0);
  EXPECT_GT(std::count(c.count.begin(), c.count.end(), 0), 0);
}

// w = -1 at every vertex, x/w, y/w, z/w inside the volume: culled before setup as behind
// the eye; and set up and traversed anyway, the sign rule alone draws no sample (every
// point of the plane through the three has w < 0).
TEST(Homogeneous, BehindTheEyeDrawsNothing) {
  const RasterState st = homogeneous_state(64, 64);
  const std::array<ClipVertex, 3> v{cv(0.5f, 0.5f, -0.5f, -1), cv(-0.5f, 0.5f, -0.5f, -1), cv(0, -0.5f, -0.5f, -1)};
  const auto c = render_coverage({tri({v[0], v[1], v[2]})}, st);
  EXPECT_EQ(c.stats.front_end.triangles_behind, 1u);
  EXPECT_EQ(c.stats.traversal.fragments, 0u);
  HomogeneousTriangle t;
  ASSERT_EQ(setup_homogeneous(v, ClipState{}, st, SourceLoc{"test", 1}, t), SetupOutcome::Accepted);
  EXPECT_EQ(t.region, (PixelRect{0, 0, 64, 64}));  // a w <= 0 vertex: no screen box
  TraversalCounters tc;
  int drawn = 0;
  rasterize_homogeneous(t, 16, tc, [&](const Fragment&) { ++drawn; });
  EXPECT_EQ(drawn, 0);
  EXPECT_EQ(tc.tiles_visited, 16u);
}

// Two vertices behind the eye, one in front (tb/test_front_end.cpp
// CrossingTheEyePlaneDrawsOnlyTheFront, worked there): the near plane z = 0 meets the
// edges at (40, 40) and (24, 40), so exactly the screen triangle (32,32) (40,40) (24,40)
// is drawn (its diagonal edges run through pixel centres: the top-left rule decides them
// as it does for the screen triangle), and nothing of the reflected part above row 32.
TEST(Homogeneous, CrossingTheEyePlaneDrawsOnlyTheFront) {
  const RasterState st = homogeneous_state(64, 64);
  const auto c =
      render_coverage({tri({cv(0, 0, 0.5f, 1), cv(0.5f, 0.5f, -1.5f, -1), cv(-0.5f, 0.5f, -1.5f, -1)})}, st);
  CmdPrimitives screen;
  for (auto [x, y] : {std::pair{32, 32}, {40, 40}, {24, 40}}) {
    SceneVertex sv;
    sv.x = Q64::from_int(x);
    sv.y = Q64::from_int(y);
    screen.vertices.push_back(sv);
  }
  const auto want = render_coverage({screen}, st);
  EXPECT_GT(want.stats.traversal.fragments, 0u);
  EXPECT_EQ(c.count, want.count);
}

// Screen (0,0) (64,0) (0,64) on 64 x 64, w = 1, 3, 1; red 255 at the w = 3 vertex only;
// z/w = 1/4, 3/4, 1/4. Row 0, pixel centre (px + 1/2, 1/2): screen barycentrics
// s1 = (2px + 1)/128, s2 = 1/128, s0 = (126 - 2px)/128; perspective-correct b1 =
// (s1/3) / (s0 + s1/3 + s2) = (2px + 1) / (382 - 4px), so red = round_half_up(255 b1);
// depth z/w = 1/4 + s1/2 = (2px + 65)/256, linear on screen, in (2^24 - 1) units.
TEST(Homogeneous, PerspectiveColourAndDepthHandWorked) {
  RasterState st = homogeneous_state(64, 64);
  st.perspective = true;
  const auto half_up = [](int64_t n, int64_t d) { return (2 * n + d) / (2 * d); };
  for (RecipMethod recip : {RecipMethod::Exact, RecipMethod::Newton}) {
    st.recip = recip;
    std::vector<Fragment> row0;
    Scene scene;
    scene.commands.push_back(
        Command{tri({cv(-1, -1, 0.25f, 1, 0), cv(3, -3, 2.25f, 3, 255), cv(-1, 1, 0.25f, 1, 0)}), SourceLoc{"t", 1}});
    RenderStats stats;
    render_scene(scene, st, stats, [&](const Fragment& f) {
      if (f.y == 0) row0.push_back(f);
    });
    ASSERT_EQ(row0.size(), 63u);  // centres x + 1/2 < 64 - 1/2
    const int64_t one = (int64_t{1} << st.depth_bits) - 1;
    for (const Fragment& f : row0) {
      const int64_t px = f.x, red = half_up(255 * (2 * px + 1), 382 - 4 * px);
      if (recip == RecipMethod::Exact) EXPECT_EQ(f.r, red) << "px " << px;
      else EXPECT_NEAR(f.r, red, 1) << "px " << px;
      EXPECT_EQ(f.z, half_up(one * (2 * px + 65), 256)) << "px " << px;
    }
  }
}

// Depth is z/w of the vertices rounded once: at every fragment of the cube around the
// camera within 1 LSB of z/w computed here from the binary32 inputs (the clip-space
// barycentrics of the pixel centre: sum b (x - nx w) = 0, sum b (y - ny w) = 0, sum b =
// 1, Cramer's rule, long double): half an LSB of rounding and the block format's 30 bits,
// which a vertex far outside the view volume shares with its large x~ or y~ (0.66 LSB
// measured here). Without z scaled by 2^s as x and y are (x~ = x W/2), the 30 bits of z
// sat 5 bits lower (1.13 LSB on traces/3d/clip_cube.trace, 0.50 with).
TEST(Homogeneous, DepthIsZOverWRoundedOnce) {
  const RasterState st = homogeneous_state(96, 64);
  const CmdPrimitives mesh = cube_mesh(Perspective(100, 0.05, 10), 3);
  const long double one = std::ldexp(1.0L, st.depth_bits) - 1;
  long double worst = 0;
  size_t n = 0;
  for (size_t k = 0; k + 2 < mesh.clip_vertices.size(); k += 3) {
    const std::array<ClipVertex, 3> v{mesh.clip_vertices[k], mesh.clip_vertices[k + 1], mesh.clip_vertices[k + 2]};
    FrontEndStats fe;
    TraversalCounters tc;
    draw_homogeneous(tri({v[0], v[1], v[2]}), st, SourceLoc{"t", 1}, fe, tc, [](SetupOutcome) { return true; },
                     [&](const Fragment& f) {
                       const long double nx = (f.x + 0.5L - 48) / 48, ny = (f.y + 0.5L - 32) / 32;
                       long double m[3][3];
                       for (size_t i = 0; i < 3; ++i) {
                         m[0][i] = v[i].x - nx * v[i].w;
                         m[1][i] = v[i].y - ny * v[i].w;
                         m[2][i] = 1;
                       }
                       const auto det = [](const long double (&a)[3][3]) {
                         return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                                a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
                       };
                       long double zs = 0, ws = 0;
                       for (size_t i = 0; i < 3; ++i) {
                         long double c[3][3];
                         for (size_t r = 0; r < 3; ++r)
                           for (size_t j = 0; j < 3; ++j) c[r][j] = j == i ? (r == 2 ? 1 : 0) : m[r][j];
                         zs += det(c) * v[i].z;
                         ws += det(c) * v[i].w;
                       }
                       worst = std::max(worst, std::fabs(f.z - one * zs / ws));
                       ++n;
                     });
  }
  EXPECT_EQ(n, 96u * 64u);
  EXPECT_LE(worst, 1.0L);
  EXPECT_GT(worst, 0.4L);  // the measure is not trivially 0
}

// A triangle fully in front whose screen vertices lie on the coordinate grid (w = 2 at
// every vertex: x/w exact in binary32): the clip method snaps them exactly, so both
// methods cover the same samples, ties on the edges included, at 1 and 4 samples; depth
// (flat, z/w = 1/2) is equal and colour within 1 LSB (the homogeneous weights are
// truncated to 63 bits, the clip method's are exact).
TEST(Homogeneous, FrontTriangleOnTheGridSameAsClip) {
  // Screen (8.25, 4.5) (50, 20.75) (13, 60) on 64 x 64: NDC (X - 32)/32, clip = 2 NDC.
  const auto v = [](double x, double y, uint8_t r) {
    return cv(float(2 * (x - 32) / 32), float(2 * (y - 32) / 32), 1.0f, 2.0f, r);
  };
  const CmdPrimitives p = tri({v(8.25, 4.5, 10), v(50, 20.75, 200), v(13, 60, 90)});
  for (int samples : {1, 4}) {
    RasterState st = homogeneous_state(64, 64);
    st.samples = samples;
    std::vector<Fragment> h, c;
    Scene scene;
    scene.commands.push_back(Command{p, SourceLoc{"t", 1}});
    RenderStats sh, sc;
    render_scene(scene, st, sh, [&](const Fragment& f) { h.push_back(f); });
    st.clip_method = ClipMethod::Clip;
    render_scene(scene, st, sc, [&](const Fragment& f) { c.push_back(f); });
    const auto key = [](const Fragment& f) { return std::pair{f.y, f.x}; };
    std::sort(h.begin(), h.end(), [&](auto& a, auto& b) { return key(a) < key(b); });
    std::sort(c.begin(), c.end(), [&](auto& a, auto& b) { return key(a) < key(b); });
    ASSERT_EQ(h.size(), c.size()) << samples << " samples";
    EXPECT_GT(h.size(), 900u);
    for (size_t i = 0; i < h.size(); ++i) {
      ASSERT_EQ(key(h[i]), key(c[i]));
      EXPECT_EQ(h[i].mask, c[i].mask);
      EXPECT_EQ(h[i].z, c[i].z);
      EXPECT_NEAR(h[i].r, c[i].r, 1);
    }
  }
}

// The levels without 2D-homogeneous rasterization (simulate, estimate, fit: the front
// end) say where it is drawn; points and lines take the clip method under it.
TEST(Homogeneous, OtherLevelsSayWhereItIsDrawn) {
  const RasterState st = homogeneous_state(64, 64);
  FrontEndStats fe;
  try {
    front_end(tri({cv(0, 0, 0.5f, 1), cv(1, 0, 0.5f, 1), cv(0, 1, 0.5f, 1)}), st, SourceLoc{"a.trace", 3}, fe,
              [](const ScreenTriangle&) {});
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("a.trace:3: clip.method = homogeneous is modelled at the reference level "
                                          "only (rastsim render)", 0), 0u) << e.what();
  }
  CmdPrimitives points;
  points.topology = Topology::Points;
  points.clip_vertices = {cv(0, 0, 0.5f, 1)};
  int n = 0;
  front_end(points, st, SourceLoc{"a.trace", 4}, fe, [&](const ScreenTriangle&) { ++n; });
  EXPECT_EQ(n, 2);
}

// A homogeneous command is drawn on one thread (no screen triangles to bin): render
// --threads 4 gives the one-thread image and stats, the front-end keys included.
TEST(Homogeneous, ThreadsAndStatsJson) {
  Scene scene;
  scene.commands.push_back(Command{cube_mesh(Perspective(100, 0.05, 10), 8), SourceLoc{"test", 1}});
  RenderStats one, four;
  render_scene(scene, homogeneous_state(96, 64), one);
  render_scene(scene, homogeneous_state(96, 64), four, {}, Framebuffer::kDefaultTileLog2, 4);
  auto j1 = to_json(one), j4 = to_json(four);
  j1.erase("wall_seconds");
  j4.erase("wall_seconds");
  EXPECT_EQ(j1, j4);
  EXPECT_EQ(j1["clip_triangles_in"], 6 * 8 * 8 * 2);
  EXPECT_EQ(j1["triangles_clipped"], 0);
  EXPECT_GT(j1["triangles_behind"], 0);
  EXPECT_EQ(one.traversal.samples_covered, 96u * 64u);  // watertight: each pixel once
}

// ---- clip versus homogeneous on random clip-space triangles ----

// One triangle's coverage: mask a pixel (py * W + px), and the pixels touched.
struct TriCoverage {
  std::vector<uint32_t> mask;
  std::vector<int> touched;
  void add(int i, uint32_t m) {
    if (!mask[size_t(i)]) touched.push_back(i);
    mask[size_t(i)] |= m;
  }
  void clear() {
    for (int i : touched) mask[size_t(i)] = 0;
    touched.clear();
  }
};

void clip_coverage(const CmdPrimitives& p, const RasterState& st, TriCoverage& out, TraversalCounters& c) {
  FrontEndStats fe;
  const TraversalParams tp = traversal_params(st);
  const SourceLoc loc{"t", 1};
  front_end(p, st, loc, fe, [&](const ScreenTriangle& v) {
    SetupTriangle t;
    if (setup_triangle(v, st, loc, t) != SetupOutcome::Accepted) return;
    traverse(t, tp, c, [&](int px, int py, uint32_t m) { out.add(py * st.fb_width + px, m); });
  });
}

void homogeneous_coverage(const CmdPrimitives& p, const RasterState& st, TriCoverage& out, TraversalCounters& c) {
  FrontEndStats fe;
  draw_homogeneous(p, st, SourceLoc{"t", 1}, fe, c, [](SetupOutcome o) { return o == SetupOutcome::Accepted; },
                   [&](const Fragment& f) { out.add(f.y * st.fb_width + f.x, f.mask); });
}

struct Comparison {
  uint64_t triangles = 0, samples_differing = 0, beyond_one_lsb = 0;
  double max_distance_lsb = 0;
  TraversalCounters clip, homogeneous;
};

// Both methods on `count` seeded triangles of each kind (the llvmpipe comparison's scenes,
// tb/mesa/clip_scenes.h) at `samples` samples a pixel; every differing sample measured
// against the exact visible polygon's edges.
Comparison compare_methods(int count, int samples) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  RasterState st = raster_state_from_config(cfg);
  st.fb_width = st.viewport_width = 240;
  st.fb_height = st.viewport_height = 160;
  st.samples = samples;
  const int F = st.coord_format.frac_bits;
  const double lsb = std::ldexp(1.0, -F);
  const SamplePattern& pat = sample_pattern(samples, F);
  Comparison r;
  TriCoverage a{std::vector<uint32_t>(240 * 160), {}}, b{std::vector<uint32_t>(240 * 160), {}};
  for (mesa::ClipKind kind : mesa::kClipKinds) {
    const uint64_t seed = 0x40e06 + uint64_t(kind);
    const mesa::ViewRect vp = mesa::make_view_rect(seed, st.fb_width, st.fb_height);
    for (const mesa::ClipTri& ct : mesa::make_clip_scene(kind, seed, count)) {
      CmdPrimitives p = tri({ct.v[0], ct.v[1], ct.v[2]});
      p.clip.xform = {false, vp.x, vp.y, vp.width, vp.height};
      a.clear();
      b.clear();
      st.clip_method = ClipMethod::Clip;
      clip_coverage(p, st, a, r.clip);
      st.clip_method = ClipMethod::Homogeneous;
      homogeneous_coverage(p, st, b, r.homogeneous);
      ++r.triangles;
      const mesa::VisiblePolygon poly(ct, vp);
      for (const TriCoverage* cov : {&a, &b})
        for (int i : cov->touched) {
          const uint32_t diff = a.mask[size_t(i)] ^ b.mask[size_t(i)];
          if (cov == &b && a.mask[size_t(i)]) continue;  // counted from a's side
          for (int s = 0; s < samples; ++s) {
            if (!((diff >> s) & 1)) continue;
            const double x = i % st.fb_width + 0.5 + double(pat.dx[size_t(s)]) * lsb;
            const double y = i / st.fb_width + 0.5 + double(pat.dy[size_t(s)]) * lsb;
            const double d = poly.edge_distance(x, y) / lsb;
            ++r.samples_differing;
            r.max_distance_lsb = std::max(r.max_distance_lsb, d);
            if (d > 1.0 + 1e-9 && ++r.beyond_one_lsb <= 10)
              ADD_FAILURE() << "sample (" << x << ", " << y << ") " << d << " LSB from every edge, clip "
                            << ((a.mask[size_t(i)] >> s) & 1) << ":\n" << mesa::describe(ct, vp);
          }
        }
    }
  }
  return r;
}

void report(const char* name, const Comparison& r) {
  std::printf("%s: %llu triangles, %llu samples differ (max %.3f LSB from an edge, %llu beyond 1 LSB)\n"
              "  clip:        %llu tiles visited, %llu sample tests, %llu samples covered\n"
              "  homogeneous: %llu tiles visited, %llu sample tests, %llu samples covered\n",
              name, (unsigned long long)r.triangles, (unsigned long long)r.samples_differing, r.max_distance_lsb,
              (unsigned long long)r.beyond_one_lsb, (unsigned long long)r.clip.tiles_visited,
              (unsigned long long)r.clip.sample_tests, (unsigned long long)r.clip.samples_covered,
              (unsigned long long)r.homogeneous.tiles_visited, (unsigned long long)r.homogeneous.sample_tests,
              (unsigned long long)r.homogeneous.samples_covered);
  ::testing::Test::RecordProperty("samples_differing", std::to_string(r.samples_differing));
}

// `count` triangles a kind at `samples` samples: every difference within one LSB of an
// edge. Figures in docs/clip-space.md, "Clip versus homogeneous".
void expect_within_one_lsb(int count, int samples, const char* name) {
  const Comparison r = compare_methods(count, samples);
  report(name, r);
  EXPECT_EQ(r.triangles, uint64_t(count) * std::size(mesa::kClipKinds));
  EXPECT_EQ(r.beyond_one_lsb, 0u);
  EXPECT_GT(r.clip.samples_covered, 2'000'000u);  // the scenes are not empty
}

TEST(Homogeneous, ClipVersusHomogeneousDifferOnlyWithinOneLsb) { expect_within_one_lsb(250, 1, "1 sample"); }

TEST(Homogeneous, ClipVersusHomogeneousFourSamplesWithinOneLsb) { expect_within_one_lsb(80, 4, "4 samples"); }

}  // namespace
}  // namespace rastsim
