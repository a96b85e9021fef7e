// SPDX-License-Identifier: Apache-2.0
// OBJ polygon faces (docs/trace-format.md, "Polygon faces"): concave faces cover exactly
// their outline, checked against a brute-force point-in-polygon on exact integers; convex
// faces keep their fan; a face crossing itself or repeating a corner is an error naming
// its line, whatever the view; and what the reader does not use is counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <unistd.h>

#include "config/raster_state_config.h"
#include "ref/fixed_point.h"
#include "ref/pipeline.h"
#include "ref/scene.h"
#include "scene/face_triangulate.h"
#include "scene/scene_io.h"
#include "scene_test.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;
using Pt = std::array<int64_t, 2>;

const std::string kData = RASTSIM_TEST_DATA;

// The default config's placement seen head-on: the view is along -z, so a face in the
// z = 0 plane keeps its shape (scaled, y flipped).
ObjPlacement head_on() {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.yaw_deg = 0;
  p.pitch_deg = 0;
  return p;
}

Scene parse(const std::string& text, const ObjPlacement& p = head_on()) { return parse_obj(text, "m.obj", p, kData); }

i128 orient(const Pt& a, const Pt& b, const Pt& c) {
  return i128(b[0] - a[0]) * (c[1] - a[1]) - i128(b[1] - a[1]) * (c[0] - a[0]);
}

bool on_segment(const Pt& a, const Pt& b, const Pt& q) {
  return orient(a, b, q) == 0 && std::min(a[0], b[0]) <= q[0] && q[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= q[1] && q[1] <= std::max(a[1], b[1]);
}

// Brute force, independent of the triangulation: q on the outline's boundary, or inside
// it by the crossing number (a ray toward +x; exact, q is not on the boundary).
bool on_boundary(const std::vector<Pt>& poly, const Pt& q) {
  for (size_t i = 0; i < poly.size(); ++i)
    if (on_segment(poly[i], poly[(i + 1) % poly.size()], q)) return true;
  return false;
}
bool inside(const std::vector<Pt>& poly, const Pt& q) {
  bool in = false;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Pt &a = poly[i], &b = poly[(i + 1) % poly.size()];
    if ((a[1] > q[1]) != (b[1] > q[1]) && (orient(a, b, q) > 0) == (b[1] > a[1])) in = !in;
  }
  return in;
}

// A star-shaped polygon about (0, 0): corner k at angle (k + 0.8 u) 2 pi / n (u uniform in
// [0, 1), so neighbouring corners are less than pi apart and (0, 0) sees every edge) and a
// random radius: simple, and concave for most draws.
std::vector<std::array<double, 2>> random_star(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> jitter(0, 0.8), radius(0.15, 1.0);
  std::vector<std::array<double, 2>> p;
  for (int k = 0; k < n; ++k) {
    const double t = (k + jitter(rng)) * 2 * std::numbers::pi / n, r = radius(rng);
    p.push_back({std::round(1000 * r * std::cos(t)) / 1000, std::round(1000 * r * std::sin(t)) / 1000});
  }
  return p;
}

// ---- The triangulation on integer outlines ----

// Every point of a fine grid that is on no triangle's edge lies in exactly one triangle
// when it is inside the outline and in none when outside; the triangles have the
// outline's orientation and together its area.
void expect_exact_cover(const std::vector<Pt>& poly, const std::vector<FaceTriangle>& tris) {
  ASSERT_EQ(tris.size(), poly.size() - 2);
  i128 area = 0, sum = 0;
  for (size_t i = 0; i < poly.size(); ++i) area += orient({0, 0}, poly[i], poly[(i + 1) % poly.size()]);
  for (const FaceTriangle& t : tris) {
    const i128 a = orient(poly[t[0]], poly[t[1]], poly[t[2]]);
    // Zero area only where the fan meets a straight corner: it covers nothing.
    EXPECT_TRUE(a == 0 || (a > 0) == (area > 0)) << "a triangle against the outline's winding";
    sum += a;
  }
  EXPECT_TRUE(sum == area) << "triangle areas do not add up to the outline's";
  int64_t lo = INT64_MAX, hi = INT64_MIN;
  for (const Pt& p : poly) lo = std::min({lo, p[0], p[1]}), hi = std::max({hi, p[0], p[1]});
  int tested = 0;
  for (int64_t y = lo; y <= hi; ++y)
    for (int64_t x = lo; x <= hi; ++x) {
      const Pt q{x, y};
      bool on_edge = false;
      int covering = 0;
      for (const FaceTriangle& t : tris) {
        const Pt &a = poly[t[0]], &b = poly[t[1]], &c = poly[t[2]];
        if (on_segment(a, b, q) || on_segment(b, c, q) || on_segment(c, a, q)) on_edge = true;
        const i128 s = orient(a, b, c);
        if (s == 0) continue;
        const bool in = (orient(a, b, q) > 0) == (s > 0) && (orient(b, c, q) > 0) == (s > 0) &&
                        (orient(c, a, q) > 0) == (s > 0);
        covering += in;
      }
      if (on_edge) continue;
      ++tested;
      ASSERT_EQ(covering, inside(poly, q) ? 1 : 0) << "at (" << x << ", " << y << ")";
    }
  EXPECT_GT(tested, 0);
}

TEST(ObjFaces, DartIsEarClippedNotFanned) {
  // The dart (-1,-1) (0,0) (1,-1) (0,2) scaled by 4: corner 1 (the notch) is reflex, so the
  // fan (0,1,2) (0,2,3) would cover the notch; ear clipping must not.
  const std::vector<Pt> dart = {{-4, -4}, {0, 0}, {4, -4}, {0, 8}};
  const FaceTriangulation t = triangulate_outline(dart);
  EXPECT_EQ(t.shape, OutlineShape::Concave);
  expect_exact_cover(dart, t.triangles);
}

TEST(ObjFaces, RandomStarsCoverExactlyTheirOutline) {
  const unsigned seed = 20261126;
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  int concave = 0;
  for (int k = 0; k < 300; ++k) {
    std::uniform_int_distribution<int> corners(4, 12);
    std::vector<Pt> poly;
    for (const auto& p : random_star(rng, corners(rng))) poly.push_back({int64_t(40 * p[0]), int64_t(40 * p[1])});
    if (k % 2) std::reverse(poly.begin(), poly.end());  // both windings
    const FaceTriangulation t = triangulate_outline(poly);
    if (t.shape == OutlineShape::Crossing || t.shape == OutlineShape::Collinear) continue;  // rounding merged corners
    SCOPED_TRACE("polygon " + std::to_string(k));
    concave += t.shape == OutlineShape::Concave;
    expect_exact_cover(poly, t.triangles);
  }
  EXPECT_GT(concave, 150);
}

TEST(ObjFaces, ConvexOutlinesKeepTheFan) {
  // A square with a straight corner (2, 0) on its bottom edge: weakly convex.
  const FaceTriangulation t = triangulate_outline({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}});
  EXPECT_EQ(t.shape, OutlineShape::Convex);
  EXPECT_EQ(t.triangles, fan_triangles(5));
  // Edge-on: every corner on one line.
  EXPECT_EQ(triangulate_outline({{0, 0}, {1, 1}, {3, 3}, {2, 2}}).shape, OutlineShape::Collinear);
}

TEST(ObjFaces, CrossingOutlinesAreFound) {
  EXPECT_EQ(triangulate_outline({{0, 0}, {4, 4}, {4, 0}, {0, 4}}).shape, OutlineShape::Crossing);  // bow-tie
  EXPECT_EQ(triangulate_outline({{0, 0}, {4, 0}, {4, 4}, {4, 4}, {0, 4}}).shape, OutlineShape::Crossing);  // repeated
  EXPECT_EQ(triangulate_outline({{0, 0}, {4, 0}, {2, 0}, {2, 4}}).shape, OutlineShape::Crossing);  // folds back
  // A pentagram: every turn the same way, but it winds twice.
  std::vector<Pt> star;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * std::numbers::pi * (2 * k % 5) / 5;
    star.push_back({int64_t(std::lround(100 * std::cos(a))), int64_t(std::lround(100 * std::sin(a)))});
  }
  EXPECT_EQ(triangulate_outline(star).shape, OutlineShape::Crossing);
}

// ---- Through the loader and the reference pipeline ----

// The corners' snapped positions, matched to the OBJ vertices by screen x then y: the
// head-on placement is x -> W/2 + s x, y -> H/2 - s y with s > 0, which keeps the order of
// x and reverses that of y.
std::vector<Pt> placed_outline(const Scene& s, const std::vector<std::array<double, 2>>& obj, const RasterState& st) {
  std::vector<Pt> seen;
  for (const Command& c : s.commands)
    if (const auto* p = std::get_if<CmdPrimitives>(&c.body))
      for (const SceneVertex& v : p->vertices) {
        const Pt q{*snap_coord(v.x, st.origin_x(), st.coord_format), *snap_coord(v.y, st.origin_y(), st.coord_format)};
        if (std::find(seen.begin(), seen.end(), q) == seen.end()) seen.push_back(q);
      }
  EXPECT_EQ(seen.size(), obj.size());
  std::sort(seen.begin(), seen.end());
  std::vector<size_t> order(obj.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return obj[a][0] != obj[b][0] ? obj[a][0] < obj[b][0] : obj[a][1] > obj[b][1];
  });
  std::vector<Pt> outline(obj.size());
  for (size_t k = 0; k < order.size() && k < seen.size(); ++k) outline[order[k]] = seen[k];
  return outline;
}

struct CoverCount {
  int wrong = 0, on_edge = 0, inside = 0;
};

// Renders the one-face OBJ and compares every pixel with the brute force at its centre.
// Centres exactly on the outline are left out and counted: which of them are drawn is the
// fill rule's business (tb/test_fill_rule.cpp), not the triangulation's. A centre on an
// inner diagonal is drawn once by the same rule, so it is compared like any other.
CoverCount compare_with_brute_force(const std::vector<std::array<double, 2>>& obj) {
  std::string text;
  for (const auto& p : obj) text += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " 0\n";
  text += "f";
  for (size_t i = 1; i <= obj.size(); ++i) text += " " + std::to_string(i);
  const Scene s = parse(text + "\n");
  const RasterState st = raster_state_from_config(Config{});
  RenderStats stats;
  const Framebuffer fb = render_scene(s, st, stats);
  const std::vector<Pt> poly = placed_outline(s, obj, st);
  const int64_t half = int64_t{1} << (st.coord_format.frac_bits - 1);
  CoverCount n;
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const Pt q{(x - st.origin_x()) * 2 * half + half, (y - st.origin_y()) * 2 * half + half};
      if (on_boundary(poly, q)) {
        ++n.on_edge;
        continue;
      }
      const uint8_t* c = fb.pixel(x, y);
      const bool drawn = c[0] != 0 || c[1] != 0 || c[2] != 0;
      n.inside += inside(poly, q);
      n.wrong += drawn != inside(poly, q);
    }
  return n;
}

TEST(ObjFaces, DartCoversExactlyItsPixels) {
  // The face of the report: fanned from its first corner it filled the notch too.
  const CoverCount n = compare_with_brute_force({{-1, -1}, {0, 0}, {1, -1}, {0, 2}});
  EXPECT_EQ(n.wrong, 0);
  EXPECT_GT(n.inside, 1000);
  EXPECT_LT(n.on_edge, 10);
}

TEST(ObjFaces, RandomStarsRenderExactly) {
  const unsigned seed = 4242;
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (int k = 0; k < 40; ++k) {
    std::uniform_int_distribution<int> corners(4, 12);
    auto star = random_star(rng, corners(rng));
    if (k % 2) std::reverse(star.begin(), star.end());
    bool tie = false;  // placed_outline matches corners by x: keep x distinct
    for (size_t i = 0; i < star.size(); ++i)
      for (size_t j = 0; j < i; ++j) tie = tie || star[i][0] == star[j][0];
    if (tie) continue;
    SCOPED_TRACE("polygon " + std::to_string(k));
    EXPECT_EQ(compare_with_brute_force(star).wrong, 0);
  }
}

TEST(ObjFaces, ConcaveFaceKeepsItsWinding) {
  // Counter-clockwise seen from +z (front-facing): every triangle CCW on screen, i.e. a
  // negative doubled area in y-down coordinates; and the reverse face all CW.
  const std::string dart = "v -1 -1 0\nv 0 0 0\nv 1 -1 0\nv 0 2 0\n";
  for (const char* f : {"f 1 2 3 4\n", "f 4 3 2 1\n"}) {
    const Scene s = parse(dart + f);
    const auto& v = std::get<CmdPrimitives>(s.commands.at(2).body).vertices;
    ASSERT_EQ(v.size(), 6u);
    for (size_t t = 0; t < 6; t += 3) {
      const double a = (v[t + 1].x.to_double() - v[t].x.to_double()) * (v[t + 2].y.to_double() - v[t].y.to_double()) -
                       (v[t + 1].y.to_double() - v[t].y.to_double()) * (v[t + 2].x.to_double() - v[t].x.to_double());
      EXPECT_EQ(a > 0, f[2] == '4') << f << " triangle " << t / 3;
    }
  }
}

TEST(ObjFaces, SelfCrossingAndRepeatedCornersAreErrors) {
  const std::string square = "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-4
  EXPECT_TRUE(SceneFails([&] { parse(square + "f 1 2 3 4\n"); }, "m.obj:5:", "the face crosses itself: edges 1-2 and 3-4"));
  EXPECT_TRUE(SceneFails([&] { parse(square + "f 1 3 2 4\nf 1 2 3 1\n"); }, "m.obj:6:",
                         "face vertex 4 '1' is vertex 1 again (face vertex 1)"));
  EXPECT_TRUE(SceneFails([&] { parse(square + "f 2 2 3\n"); }, "m.obj:5:", "is vertex 2 again"));
  // Two corners at one position (distinct vertex lines).
  EXPECT_TRUE(SceneFails([&] { parse(square + "v 1 0 0\nf 1 3 5 2 4\n"); }, "m.obj:6:", "corners 2-3 are at one position"));
  // The same bow-tie seen edge-on is still an error: the test is in the face's plane.
  ObjPlacement side = head_on();
  side.yaw_deg = 90;
  EXPECT_TRUE(SceneFails([&] { parse(square + "f 1 2 3 4\n", side); }, "m.obj:5:", "crosses itself"));
}

TEST(ObjFaces, EdgeOnConcaveFaceDrawsNothingAndLoads) {
  // The dart in the x = 0 plane, seen along -z: a line on screen.
  ObjPlacement p = head_on();
  const Scene s = parse("v 0 -1 -1\nv 0 0 0\nv 0 -1 1\nv 0 2 0\nv 1 0 0\nf 1 2 3 4\nf 5 2 4\n", p);
  const RasterState st = raster_state_from_config(Config{});
  RenderStats stats;
  render_scene(s, st, stats);
  EXPECT_EQ(stats.triangles_in, 3u);
  EXPECT_EQ(stats.triangles_zero_area, 2u);
}

// ---- Points, lines and what is not used ----

TEST(ObjStatements, LinesAndPointsStopUnlessSkipped) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_TRUE(SceneFails([&] { parse(tri + "l 1 2\n"); }, "m.obj:5:",
                         "'l' (polyline) statements are drawn by the perspective camera only"));
  EXPECT_TRUE(SceneFails([&] { parse(tri + "\np 1\n"); }, "m.obj:6:", "scene.obj_lines_points = \"skip\""));
  ObjPlacement skip = head_on();
  skip.lines_points = ObjLinesPoints::Skip;
  const Scene s = parse(tri + "l 1 2 3\np 1\np 2\n", skip);
  EXPECT_EQ(s.obj_ignored, (StatementCounts{{"l", 1}, {"p", 2}}));
  EXPECT_EQ(s.commands.size(), 3u);  // the triangle only
}

TEST(ObjStatements, ConfigKeyChoosesSkip) {
  Config cfg;
  EXPECT_EQ(obj_placement_from_config(cfg).lines_points, ObjLinesPoints::Error);
  cfg.set_from_string("scene.obj_lines_points", "skip", "test");
  EXPECT_EQ(obj_placement_from_config(cfg).lines_points, ObjLinesPoints::Skip);
}

TEST(ObjStatements, UnusedStatementsAreCounted) {
  // Hand count of tb/data/cube.obj and cube.mtl (its vt and map_Kd are used: textures).
  const StatementCounts want = {{"vn", 2}, {"o", 1}, {"s", 1}, {"g", 1}, {"Ka", 1},
                                {"Ks", 1}, {"Ns", 1}, {"illum", 1}, {"d", 1}};
  testing::internal::CaptureStderr();
  const Scene s = load_obj(kData + "/cube.obj", head_on());
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(s.obj_ignored, want);
  EXPECT_EQ(err, kData + "/cube.obj: ignored: Ka 1, Ks 1, Ns 1, d 1, g 1, illum 1, o 1, s 1, vn 2\n");
  EXPECT_EQ(obj_ignored_counts(kData + "/cube.obj"), want);
  EXPECT_EQ(obj_ignored_counts(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace"), std::nullopt);
  // Nothing unused: no line on stderr.
  testing::internal::CaptureStderr();
  EXPECT_TRUE(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").obj_ignored.empty());
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(ObjStatements, MissingTextureMapNamesTheMtlLine) {
  const auto dir = std::filesystem::temp_directory_path() / ("rastsim_obj_maps_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream((dir / "m.mtl").string()) << "newmtl a\nKd 1 1 1\nmap_Ks -s 1 1 1 there.png\nbump gone.png\n";
  std::ofstream((dir / "there.png").string()) << "x";
  EXPECT_TRUE(SceneFails([&] { parse_obj("mtllib m.mtl\n", "x.obj", head_on(), dir.string()); },
                         (dir / "m.mtl").string() + ":4:", "'bump' names 'gone.png', which does not exist"));
  std::filesystem::remove_all(dir);
}

TEST(ObjStatements, ByteOrderMarkIsAccepted) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Scene plain = parse(tri), bom = parse("\xEF\xBB\xBF" + tri);
  ASSERT_EQ(bom.commands.size(), plain.commands.size());
  EXPECT_EQ(std::get<CmdPrimitives>(bom.commands[2].body).vertices[1].x.q,
            std::get<CmdPrimitives>(plain.commands[2].body).vertices[1].x.q);
  // Only at the start: elsewhere it is not whitespace.
  EXPECT_TRUE(SceneFails([&] { parse(tri + "\xEF\xBB\xBF" + "v 1 1 1\n"); }, "m.obj:5:", "unknown OBJ statement"));
}

}  // namespace
}  // namespace rastsim
