// SPDX-License-Identifier: Apache-2.0
// Triangle traversal methods (raster.traversal, docs/traversal.md) against the exact
// coverage.
//
// - Per triangle: thousands of seeded random triangles (uniform, slivers, vertices on
//   tile corners and pixel centres, guard-band vertices, several formats and hierarchy
//   levels). The SET of pixels each exact method emits (bbox, hierarchical, tiled) must
//   equal a brute-force scan of pixel_covered over the whole clip rectangle, with no
//   pixel emitted twice; the order is not compared (it differs by method).
// - Per scene: random shared-edge meshes (jittered grids) and the random scenes of the
//   fragment tests render with every exact method to the tiled framebuffer CRC and the
//   same multiset of fragment-trace lines ("x y z r g b", sorted).
// - Scanline: errors only next to an edge (each wrong pixel's centre within a small
//   distance of some edge line), counted exactly (pixels_wrong equals an independent
//   count of the symmetric difference against the brute-force scan); CoverageCheck's
//   cracks / overlaps on hand-made pixel sets.
// - Config: the keys, their errors, and the stats JSON keys present only where they apply.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/traverse.h"
#include "report/stats_json.h"

namespace rastsim {
namespace {

using PixelSet = std::set<std::pair<int, int>>;

// Absolute raw coordinate (units 2^-F px from the framebuffer's top-left) as a scene value.
Q64 q_of_raw(int64_t raw, int F) { return Q64{i128(raw) << (Q64::kFracBits - F)}; }

struct TriGen {
  std::mt19937_64 rng;
  int F, vw, vh, tile;
  int64_t reach;  // raw; keep vertices within the format around the origin
  int64_t uni(int64_t lo, int64_t hi) { return lo + int64_t(rng() % uint64_t(hi - lo + 1)); }
  // One coordinate, absolute raw, of one of several kinds.
  int64_t coord(int n_px, int kind) {
    const int64_t one = int64_t{1} << F;
    const int64_t lo = -one * 8, hi = one * (n_px + 8);  // a little guard band
    switch (kind) {
      case 0: return uni(lo, hi);                                                  // anywhere on the grid
      case 1: return uni(-1, n_px / tile + 1) * tile * one;                        // tile corner
      case 2: return uni(-2, n_px + 2) * one + one / 2;                            // pixel centre
      default: return uni(-2, n_px + 2) * one + (rng() % 2 ? 1 : -1) * uni(0, 2);  // near a pixel corner
    }
  }
  std::array<SceneVertex, 3> triangle() {
    std::array<SceneVertex, 3> v;
    const int kind = int(rng() % 5);
    int64_t ax[3], ay[3];
    for (int i = 0; i < 3; ++i) {
      const int k = kind == 4 ? int(rng() % 4) : kind;
      ax[i] = coord(vw, k);
      ay[i] = coord(vh, k);
    }
    if (rng() % 4 == 0) {  // sliver: the third vertex a few LSBs off the line of the first two
      const int64_t t = uni(0, 1024);
      ax[2] = ax[0] + (ax[1] - ax[0]) * t / 1024 + uni(-2, 2);
      ay[2] = ay[0] + (ay[1] - ay[0]) * t / 1024 + uni(-2, 2);
    }
    for (int i = 0; i < 3; ++i) {
      v[i].x = q_of_raw(ax[i], F);
      v[i].y = q_of_raw(ay[i], F);
      v[i].z = 0.5;
    }
    return v;
  }
};

RasterState state_for(const std::vector<std::string>& sets) {
  Config cfg;
  for (const auto& s : sets) cfg.apply_override(s);
  return raster_state_from_config(cfg);
}

PixelSet brute_force(const SetupTriangle& t, const RasterState& st) {
  PixelSet s;
  const PixelRect clip = st.clip_rect();
  for (int y = clip.y0; y < clip.y1; ++y)
    for (int x = clip.x0; x < clip.x1; ++x)
      if (pixel_covered(t, x, y, st.coord_format.frac_bits)) s.insert({x, y});
  return s;
}

// Emits of one method as a set; fails on a repeated pixel or one outside the clip.
PixelSet emitted(const SetupTriangle& t, const RasterState& st) {
  PixelSet s;
  TraversalCounters c;
  const PixelRect clip = st.clip_rect();
  traverse(t, traversal_params(st), c, [&](int x, int y) {
    EXPECT_TRUE(x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1) << x << "," << y;
    EXPECT_TRUE(s.insert({x, y}).second) << "pixel emitted twice: " << x << "," << y;
  });
  EXPECT_EQ(c.fragments, s.size());
  EXPECT_EQ(c.tiles_visited, c.tiles_rejected + c.tiles_accepted + c.tiles_partial);
  return s;
}

struct ExactCase {
  const char* name;
  std::string format, levels;
  int vw, vh, tile;
};
void PrintTo(const ExactCase& c, std::ostream* os) { *os << c.name; }

class ExactTraversal : public ::testing::TestWithParam<ExactCase> {};

TEST_P(ExactTraversal, EverySetEqualsBruteForce) {
  const ExactCase& k = GetParam();
  const uint64_t seed = 0x7a5 + k.vw;
  std::cout << "seed " << seed << "\n";
  std::vector<std::string> base{"raster.coord_format=" + k.format, "display.width=" + std::to_string(k.vw),
                                "display.height=" + std::to_string(k.vh), "raster.tile_size=" + std::to_string(k.tile),
                                "raster.hier_levels=" + k.levels, "raster.out_of_range=cull"};
  const RasterState tiled = state_for(base);
  auto with = [&](const char* m) {
    auto s = base;
    s.push_back(std::string("raster.traversal=") + m);
    return state_for(s);
  };
  const RasterState bbox = with("bbox"), hier = with("hierarchical");
  TriGen gen{std::mt19937_64(seed), tiled.coord_format.frac_bits, k.vw, k.vh, k.tile, 0};
  int accepted = 0;
  for (int i = 0; i < 3000; ++i) {
    SCOPED_TRACE("triangle " + std::to_string(i));
    const auto v = gen.triangle();
    SetupTriangle t;
    if (setup_triangle(v, tiled, SourceLoc{}, t) != SetupOutcome::Accepted) continue;
    ++accepted;
    const PixelSet truth = brute_force(t, tiled);
    ASSERT_EQ(emitted(t, tiled), truth);
    ASSERT_EQ(emitted(t, bbox), truth);
    ASSERT_EQ(emitted(t, hier), truth);
  }
  EXPECT_GT(accepted, 1500);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ExactTraversal,
    ::testing::Values(ExactCase{"s7_16_64_16_4", "s7.16", "64/16/4", 96, 80, 16},
                      ExactCase{"s11_4_32_8_2", "s11.4", "32/8/2", 70, 50, 8},
                      ExactCase{"s9_8_16", "s9.8", "16", 64, 64, 4},
                      ExactCase{"s5_24_128_4", "s5.24", "128/4", 40, 40, 32}),
    [](const auto& info) { return std::string(info.param.name); });

// A jittered grid over the viewport (plus a border in the guard band), each quad split
// along a random diagonal, in one triangle list: a mesh whose triangles share edges.
Scene grid_mesh(uint64_t seed, int vw, int vh, int F, int cells) {
  std::mt19937_64 rng(seed);
  const int64_t one = int64_t{1} << F;
  const int n = cells + 1;
  std::vector<int64_t> gx(size_t(n) * n), gy(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Cell corners spread over [-2, vw + 2], interior ones jittered by < a fifth of a cell
      // (with the pixel-centre / corner moves below, every quad stays convex).
      const int64_t cx = (-2 * one) + (vw + 4) * one * i / cells, cy = (-2 * one) + (vh + 4) * one * j / cells;
      const int64_t jx = (vw + 4) * one / cells / 5, jy = (vh + 4) * one / cells / 5;
      const bool inner = i > 0 && j > 0 && i < cells && j < cells;
      int64_t x = cx + (inner ? int64_t(rng() % uint64_t(2 * jx + 1)) - jx : 0);
      int64_t y = cy + (inner ? int64_t(rng() % uint64_t(2 * jy + 1)) - jy : 0);
      if (inner && rng() % 4 == 0) x = (x >> F << F) + one / 2;  // on a pixel-centre column
      if (inner && rng() % 4 == 0) y = y >> F << F;               // on a pixel-corner row
      gx[size_t(j) * n + i] = x;
      gy[size_t(j) * n + i] = y;
    }
  CmdPrimitives p;
  auto vert = [&](int i, int j) {
    SceneVertex v;
    v.x = q_of_raw(gx[size_t(j) * n + i], F);
    v.y = q_of_raw(gy[size_t(j) * n + i], F);
    v.z = double((i * 7 + j * 13) % 17) / 17.0;
    v.r = uint8_t(i * 40);
    v.g = uint8_t(j * 40);
    v.b = uint8_t(rng());
    return v;
  };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const auto a = vert(i, j), b = vert(i + 1, j), c = vert(i + 1, j + 1), d = vert(i, j + 1);
      if (rng() % 2) {
        for (const auto& v : {a, b, c, a, c, d}) p.vertices.push_back(v);
      } else {
        for (const auto& v : {a, b, d, b, c, d}) p.vertices.push_back(v);
      }
    }
  Scene s;
  s.commands.push_back({CmdViewport{vw, vh}, {}});
  s.commands.push_back({CmdClear{1, 2, 3}, {}});
  s.commands.push_back({std::move(p), {}});
  return s;
}

struct Rendered {
  uint32_t crc = 0;
  std::vector<std::string> fragments;  // sorted
  RenderStats stats;
};
Rendered render_with(const Scene& scene, const std::vector<std::string>& sets) {
  Rendered r;
  const RasterState st = state_for(sets);
  render_scene(scene, st, r.stats, [&](const Fragment& f) { r.fragments.push_back(fragment_trace_line(f)); });
  r.crc = r.stats.framebuffer_crc32;
  std::sort(r.fragments.begin(), r.fragments.end());
  return r;
}

TEST(TraversalScenes, ExactMethodsMatchTiledOnSharedEdgeMeshes) {
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string fmt = seed % 3 == 0 ? "s11.4" : "s7.16";
    const int F = seed % 3 == 0 ? 4 : 16;
    const Scene scene = grid_mesh(seed, 100, 90, F, 3 + int(seed % 7));
    const std::vector<std::string> base{"display.width=100", "display.height=90", "raster.coord_format=" + fmt,
                                        "raster.depth_func=less"};
    const Rendered tiled = render_with(scene, base);
    // Watertight: every pixel exactly once (the mesh covers the viewport).
    ASSERT_EQ(tiled.fragments.size(), 100u * 90u);
    for (const char* m : {"traversal=bbox", "traversal=hierarchical", "hier_levels=32/4", "hier_levels=8"}) {
      SCOPED_TRACE(m);
      auto sets = base;
      sets.push_back(std::string("raster.") + m);
      if (std::string(m).rfind("hier_levels", 0) == 0) sets.push_back("raster.traversal=hierarchical");
      const Rendered r = render_with(scene, sets);
      EXPECT_EQ(r.crc, tiled.crc);
      EXPECT_EQ(r.fragments, tiled.fragments);
    }
  }
}

// The scanline method: its errors lie next to an edge, and pixels_wrong counts them.
struct ScanCase {
  const char* arith;
  double max_edge_distance_px;  // a wrong pixel's centre lies this close to an edge line
};

class ScanlineErrors : public ::testing::TestWithParam<ScanCase> {};

TEST_P(ScanlineErrors, WrongPixelsLieOnEdgesAndAreCounted) {
  const ScanCase& k = GetParam();
  const uint64_t seed = 99;
  std::cout << "seed " << seed << "\n";
  const std::vector<std::string> sets{"display.width=96", "display.height=80", "raster.traversal=scanline",
                                      std::string("raster.scanline_arith=") + k.arith};
  const RasterState st = state_for(sets);
  const int F = st.coord_format.frac_bits;
  TriGen gen{std::mt19937_64(seed), F, 96, 80, 16, 0};
  uint64_t wrong = 0, total = 0;
  Scene scene;
  scene.commands.push_back({CmdViewport{96, 80}, {}});
  for (int i = 0; i < 3000; ++i) {
    const auto v = gen.triangle();
    SetupTriangle t;
    if (setup_triangle(v, st, SourceLoc{}, t) != SetupOutcome::Accepted) continue;
    CmdPrimitives p;
    p.vertices.assign(v.begin(), v.end());
    scene.commands.push_back({std::move(p), {}});
    const PixelSet truth = brute_force(t, st), got = emitted(t, st);
    total += truth.size();
    std::vector<std::pair<int, int>> diff;
    std::set_symmetric_difference(truth.begin(), truth.end(), got.begin(), got.end(), std::back_inserter(diff));
    wrong += diff.size();
    for (const auto& [x, y] : diff) {
      // Distance in px from the pixel centre to the nearest edge line (exact value, as double).
      double best = 1e30;
      for (const auto& e : t.edge) {
        const double ev = double(e.eval(t.sample_x(x, F), t.sample_y(y, F)));
        best = std::min(best, std::abs(ev) / std::hypot(double(e.a), double(e.b)) / std::ldexp(1.0, F));
      }
      EXPECT_LE(best, k.max_edge_distance_px) << "wrong pixel " << x << "," << y << " of triangle " << i;
    }
  }
  // The pipeline's count is the same symmetric difference, summed.
  RenderStats stats;
  render_scene(scene, st, stats);
  EXPECT_TRUE(stats.coverage.measured);
  EXPECT_EQ(stats.coverage.pixels_wrong, wrong);
  std::cout << k.arith << ": " << wrong << " wrong of " << total << " exact pixels\n";
  EXPECT_LT(double(wrong), 0.01 * double(total));
}

INSTANTIATE_TEST_SUITE_P(Arith, ScanlineErrors,
                         ::testing::Values(ScanCase{"f32", 1e-3}, ScanCase{"f64", 1e-9}, ScanCase{"fixed", 1e-3}),
                         [](const auto& info) { return std::string(info.param.arith); });

// Hand-worked: the right triangle (0, 0) (10, 0) (0, 10) px relative to the origin
// (64, 64) of a 128 x 128 viewport, in centre coordinates (63.5, 63.5) (73.5, 63.5)
// (63.5, 73.5). Row y (64..73) runs from the left edge x = 63.5 to the hypotenuse
// x = 137 - y: pixels ceil(63.5) = 64 to ceil(137 - y) - 1, i.e. [64, 137 - y); the
// centre on the hypotenuse (a right edge) is out, so row 73 is empty. Every arithmetic
// holds these values exactly.
TEST(ScanlineSpans, HandWorkedRightTriangle) {
  for (const char* arith : {"f32", "f64", "fixed"}) {
    SCOPED_TRACE(arith);
    const RasterState st = state_for({std::string("raster.scanline_arith=") + arith, "raster.traversal=scanline"});
    std::array<SceneVertex, 3> v;
    const int px[3][2] = {{64, 64}, {74, 64}, {64, 74}};  // absolute px
    for (int i = 0; i < 3; ++i) {
      v[i].x = Q64::from_int(px[i][0]);
      v[i].y = Q64::from_int(px[i][1]);
    }
    SetupTriangle t;
    ASSERT_EQ(setup_triangle(v, st, SourceLoc{}, t), SetupOutcome::Accepted);
    std::vector<std::array<int, 3>> spans;
    scanline_spans(t, st.scanline_arith, 16, [&](int y, int x0, int x1) { spans.push_back({y, x0, x1}); });
    ASSERT_EQ(spans.size(), 10u);
    for (int y = 64; y <= 73; ++y) {
      const auto& sp = spans[size_t(y - 64)];
      EXPECT_EQ(sp[0], y);
      EXPECT_EQ(sp[1], 64);
      EXPECT_EQ(std::max(sp[1], sp[2]), 137 - y);
    }
    EXPECT_EQ(emitted(t, st), brute_force(t, st));
  }
}

// One hierarchy level equal to the tile size is the tiled walk: same order, same counters.
TEST(HierarchicalTraversal, OneLevelIsTiled) {
  const Scene scene = grid_mesh(11, 100, 90, 16, 6);
  for (int tile : {4, 16, 64}) {
    SCOPED_TRACE(tile);
    const std::vector<std::string> base{"display.width=100", "display.height=90",
                                        "raster.tile_size=" + std::to_string(tile)};
    RenderStats a, b;
    std::vector<std::string> fa, fb;
    render_scene(scene, state_for(base), a, [&](const Fragment& f) { fa.push_back(fragment_trace_line(f)); });
    auto sets = base;
    sets.insert(sets.end(), {"raster.traversal=hierarchical", "raster.hier_levels=" + std::to_string(tile)});
    render_scene(scene, state_for(sets), b, [&](const Fragment& f) { fb.push_back(fragment_trace_line(f)); });
    EXPECT_EQ(fa, fb);  // in order
    EXPECT_EQ(a.traversal.tiles_visited, b.traversal.tiles_visited);
    EXPECT_EQ(a.traversal.tiles_accepted, b.traversal.tiles_accepted);
    EXPECT_EQ(a.traversal.tiles_partial, b.traversal.tiles_partial);
    EXPECT_EQ(a.traversal.pixel_tests, b.traversal.pixel_tests);
  }
}

// CoverageCheck on hand-made pixel sets for two triangles sharing the diagonal of a
// 4 x 4 square at pixels [0, 4)^2: the exact sets, one pixel dropped, one pixel doubled.
TEST(CoverageCheck, CountsWrongPixelsCracksAndOverlaps) {
  const RasterState st = state_for({"display.width=8", "display.height=8", "raster.coord_format=s7.16"});
  const int F = 16;
  auto tri = [&](std::array<std::pair<int, int>, 3> p) {
    std::array<SceneVertex, 3> v;
    for (int i = 0; i < 3; ++i) {
      v[i].x = q_of_raw(int64_t(p[i].first) << F, F);
      v[i].y = q_of_raw(int64_t(p[i].second) << F, F);
    }
    SetupTriangle t;
    EXPECT_EQ(setup_triangle(v, st, SourceLoc{}, t), SetupOutcome::Accepted);
    return t;
  };
  const SetupTriangle upper = tri({{{0, 0}, {4, 0}, {4, 4}}}), lower = tri({{{0, 0}, {4, 4}, {0, 4}}});
  auto exact = [&](const SetupTriangle& t) {
    const PixelSet s = brute_force(t, st);
    return std::vector<std::pair<int, int>>(s.begin(), s.end());
  };
  const auto up = exact(upper), lo = exact(lower);
  ASSERT_EQ(up.size() + lo.size(), 16u);  // the square, each pixel once
  {
    CoverageCheck chk(8, 8);
    CoverageErrors e;
    chk.add_triangle(upper, F, up, e);
    chk.add_triangle(lower, F, lo, e);
    chk.finish(e);
    EXPECT_EQ(e.pixels_wrong, 0u);
    EXPECT_EQ(e.cracks, 0u);
    EXPECT_EQ(e.overlaps, 0u);
  }
  {  // the lower triangle loses a diagonal pixel, the upper one takes a pixel of the lower
    auto lo2 = lo;
    const auto dropped = lo2.back();
    lo2.pop_back();
    auto up2 = up;
    up2.push_back(lo.front());  // inside the upper bbox (the whole square)
    CoverageCheck chk(8, 8);
    CoverageErrors e;
    chk.add_triangle(upper, F, up2, e);
    chk.add_triangle(lower, F, lo2, e);
    chk.finish(e);
    EXPECT_EQ(e.pixels_wrong, 2u);
    EXPECT_EQ(e.cracks, dropped == lo.front() ? 0u : 1u);
    EXPECT_EQ(e.overlaps, 1u);
  }
}

TEST(TraversalConfig, KeysValidateWithClearErrors) {
  auto error_of = [](const std::string& set) -> std::string {
    try {
      Config c;
      c.apply_override(set);
      c.validate();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of("raster.hier_levels=64/16/4"), "");
  EXPECT_EQ(error_of("raster.hier_levels=8"), "");
  for (const char* bad : {"raster.hier_levels=64/32/32", "raster.hier_levels=16/64", "raster.hier_levels=48/16",
                          "raster.hier_levels=", "raster.hier_levels=64/", "raster.hier_levels=1",
                          "raster.hier_levels=2048", "raster.hier_levels=64,16"}) {
    SCOPED_TRACE(bad);
    EXPECT_NE(error_of(bad).find("powers of two"), std::string::npos) << error_of(bad);
  }
  EXPECT_NE(error_of("raster.traversal=zigzag").find("tiled, bbox, hierarchical, scanline"), std::string::npos);
  EXPECT_NE(error_of("raster.scanline_arith=f16").find("f32, f64, fixed"), std::string::npos);
  Config c;
  c.apply_override("raster.traversal=scanline");
  c.apply_override("raster.fill_rule=exclusive");
  EXPECT_THROW(c.validate(), ConfigError);
  const std::string doc = config_doc();
  for (const char* k : {"raster.traversal", "raster.hier_levels", "raster.scanline_arith",
                        "coarse.scanline_setup_cycles", "fine.span_setup_cycles", "fine.span_pixels_per_cycle"})
    EXPECT_NE(doc.find(k), std::string::npos) << k;
}

TEST(TraversalStats, ErrorKeysOnlyForInexactMethod) {
  const Scene scene = grid_mesh(5, 64, 64, 16, 4);
  auto json_of = [&](const char* m) {
    return to_json(render_with(scene, {"display.width=64", "display.height=64", std::string("raster.traversal=") + m})
                       .stats);
  };
  const auto tiled = json_of("tiled"), bbox = json_of("bbox"), scan = json_of("scanline");
  for (const char* k : {"pixels_wrong", "cracks", "overlaps", "traversal", "spans"}) {
    EXPECT_FALSE(tiled.contains(k)) << k;
    EXPECT_FALSE(bbox.contains(k) && std::string(k) != "traversal") << k;
    EXPECT_TRUE(scan.contains(k)) << k;
  }
  EXPECT_EQ(bbox["traversal"], "bbox");
  EXPECT_EQ(bbox["framebuffer_crc32"], tiled["framebuffer_crc32"]);
}

}  // namespace
}  // namespace rastsim
