// SPDX-License-Identifier: Apache-2.0
// Hand-worked fill-rule, culling, clipping, interpolation and depth cases.
//
// Every expected value here was worked out by hand from the geometry (the reasoning is
// in the comment above each case): coverage maps are drawn with '#' for a pixel hit
// once, '.' for none, and a digit for a pixel hit that many times. y grows downward and
// pixel (px, py) has its centre at (px + 1/2, py + 1/2). Direct3D 11 top-left rule: a
// centre exactly on an edge is covered only for a top edge (horizontal, triangle below)
// or a left edge (triangle to its right).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/rop.h"
#include "ref/tri_setup.h"

namespace rastsim {
namespace {

// A vertex as decimal pixel coordinates, plus optional attributes.
struct V {
  const char* x;
  const char* y;
  std::array<uint8_t, 3> rgb{255, 255, 255};
  double z = 0.0;
};
using Tri = std::array<V, 3>;

SceneVertex scene_vertex(const V& v) {
  SceneVertex s;
  s.x = Q64::parse_decimal(v.x);
  s.y = Q64::parse_decimal(v.y);
  s.z = v.z;
  s.r = v.rgb[0];
  s.g = v.rgb[1];
  s.b = v.rgb[2];
  return s;
}

RasterState state(int w, int h) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.viewport_width = w;
  st.fb_height = st.viewport_height = h;
  st.tile_size = 4;
  return st;
}

// Renders triangles (a list) and returns the framebuffer's coverage map, one row per
// line. `pre` commands (viewport, scissor) go first.
std::string coverage_map(const std::vector<Tri>& tris, const RasterState& st, RenderStats* stats_out = nullptr,
                         std::vector<CommandBody> pre = {}) {
  Scene scene;
  for (auto& c : pre) scene.commands.push_back({std::move(c), {"hand", 1}});
  CmdPrimitives prims;
  for (const Tri& t : tris)
    for (const V& v : t) prims.vertices.push_back(scene_vertex(v));
  scene.commands.push_back({std::move(prims), {"hand", 2}});
  RenderStats stats;
  std::vector<int> hits(size_t(st.fb_width) * st.fb_height, 0);
  render_scene(scene, st, stats, [&](const Fragment& f) { ++hits[size_t(f.y) * st.fb_width + f.x]; });
  if (stats_out) *stats_out = stats;
  std::string map;
  for (int y = 0; y < st.fb_height; ++y) {
    for (int x = 0; x < st.fb_width; ++x) {
      const int h = hits[size_t(y) * st.fb_width + x];
      map += h == 0 ? '.' : h == 1 ? '#' : char('0' + std::min(h, 9));
    }
    map += '\n';
  }
  return map;
}

// The six vertex orders of a triangle: both windings, every rotation.
std::vector<Tri> orders(const Tri& t) {
  std::array<int, 3> p{0, 1, 2};
  std::vector<Tri> out;
  do out.push_back({t[p[0]], t[p[1]], t[p[2]]});
  while (std::next_permutation(p.begin(), p.end()));
  return out;
}

// Triangle A: right angle at (0.5, 0.5), legs of 4 px along the top row and left column
// of centres. Its top edge (y = 0.5, triangle below) and left edge (x = 0.5, triangle to
// the right) own their centres; the hypotenuse x + y = 5 is a right edge and does not,
// so the covered centres are px + py <= 3: 4 + 3 + 2 + 1 = 10 pixels.
const Tri kA{V{"0.5", "0.5"}, V{"4.5", "0.5"}, V{"0.5", "4.5"}};
// Triangle B completes the square [0.5, 4.5]^2: its bottom edge (y = 4.5) and right edge
// (x = 4.5) own nothing, the shared hypotenuse is its left edge: px, py <= 3 and
// px + py >= 4: 1 + 2 + 3 = 6 pixels.
const Tri kB{V{"4.5", "0.5"}, V{"4.5", "4.5"}, V{"0.5", "4.5"}};

TEST(FillRule, TopAndLeftEdgesThroughCentresAreCovered) {
  EXPECT_EQ(coverage_map({kA}, state(6, 6)),
            "####..\n"
            "###...\n"
            "##....\n"
            "#.....\n"
            "......\n"
            "......\n");
}

TEST(FillRule, BottomAndRightEdgesThroughCentresAreNotCovered) {
  EXPECT_EQ(coverage_map({kB}, state(6, 6)),
            "......\n"
            "...#..\n"
            "..##..\n"
            ".###..\n"
            "......\n"
            "......\n");
}

// A and B share the diagonal through (k + 1/2, 4 - k + 1/2): the union is the 4x4 block
// of centres inside [0.5, 4.5)^2, each exactly once.
TEST(FillRule, SharedAntiDiagonalCoversEachCentreOnce) {
  EXPECT_EQ(coverage_map({kA, kB}, state(6, 6)),
            "####..\n"
            "####..\n"
            "####..\n"
            "####..\n"
            "......\n"
            "......\n");
}

// The same square split along x = y. Upper-right C (0.5,0.5) (4.5,0.5) (4.5,4.5): top
// edge owned, right edge x = 4.5 not, and the diagonal is its left edge (the third
// vertex (4.5, 0.5) lies right of it) so px >= py: 4 + 3 + 2 + 1 = 10. Lower-left D
// owns its left edge but not the diagonal (a right edge for it) nor its bottom edge:
// px < py, py <= 3: 1 + 2 + 3 = 6.
TEST(FillRule, SharedMainDiagonalCoversEachCentreOnce) {
  const Tri c{V{"0.5", "0.5"}, V{"4.5", "0.5"}, V{"4.5", "4.5"}};
  const Tri d{V{"0.5", "0.5"}, V{"4.5", "4.5"}, V{"0.5", "4.5"}};
  EXPECT_EQ(coverage_map({c}, state(5, 5)),
            "####.\n"
            ".###.\n"
            "..##.\n"
            "...#.\n"
            ".....\n");
  EXPECT_EQ(coverage_map({d}, state(5, 5)),
            ".....\n"
            "#....\n"
            "##...\n"
            "###..\n"
            ".....\n");
  EXPECT_EQ(coverage_map({c, d}, state(5, 5)),
            "####.\n"
            "####.\n"
            "####.\n"
            "####.\n"
            ".....\n");
}

// Bottom-right is the mirror image: for A only the hypotenuse (a right edge) owns its
// centres, so px, py >= 1 and px + py <= 4: 3 + 2 + 1 = 6 pixels.
TEST(FillRule, BottomRightRuleMirrorsTopLeft) {
  RasterState st = state(6, 6);
  st.fill_rule = FillRule::BottomRight;
  EXPECT_EQ(coverage_map({kA}, st),
            "......\n"
            ".###..\n"
            ".##...\n"
            ".#....\n"
            "......\n"
            "......\n");
}

TEST(FillRule, BothWindingsAndAllRotationsGiveTheSameCoverage) {
  const Tri generic{V{"0.3", "5.7"}, V{"5.5", "1.5"}, V{"2.5", "0.2"}};
  for (const Tri& t : {kA, kB, generic}) {
    const std::string want = coverage_map({t}, state(6, 6));
    for (const Tri& o : orders(t)) {
      SCOPED_TRACE(std::string("(") + o[0].x + "," + o[0].y + ") (" + o[1].x + "," + o[1].y + ") (" + o[2].x +
                   "," + o[2].y + ")");
      EXPECT_EQ(coverage_map({o}, state(6, 6)), want);
    }
  }
}

// A vertex exactly on a pixel centre is covered only when both edges meeting there own
// it. (2.5,2.5) (3.2,2.5) (2.5,3.2): top edge + left edge meet at the centre of pixel
// (2, 2) and no other centre is inside, so exactly that pixel. Its mirror (2.5,2.5)
// (1.8,2.5) (2.5,1.8) has a bottom and a right edge there: nothing, although the
// triangle is set up and traversed. With a top and a right edge: nothing either.
TEST(FillRule, VertexOnPixelCentre) {
  EXPECT_EQ(coverage_map({{V{"2.5", "2.5"}, V{"3.2", "2.5"}, V{"2.5", "3.2"}}}, state(5, 5)),
            ".....\n"
            ".....\n"
            "..#..\n"
            ".....\n"
            ".....\n");
  RenderStats stats;
  EXPECT_EQ(coverage_map({{V{"2.5", "2.5"}, V{"1.8", "2.5"}, V{"2.5", "1.8"}}}, state(5, 5), &stats),
            ".....\n.....\n.....\n.....\n.....\n");
  EXPECT_EQ(stats.triangles_rasterized, 1u);
  EXPECT_EQ(stats.traversal.fragments, 0u);
  EXPECT_EQ(coverage_map({{V{"2.5", "2.5"}, V{"1.8", "2.5"}, V{"2.5", "3.2"}}}, state(5, 5)),
            ".....\n.....\n.....\n.....\n.....\n");
}

// Four triangles meet at the centre c = (2.5, 2.5) of pixel (2, 2), forming the diamond
// |x - 2.5| + |y - 2.5| <= 2.4. Only the lower-right one (top edge c->E, left edge c->S)
// owns c; the union covers the 13 centres with |px - 2| + |py - 2| <= 2 exactly once,
// including the row and column lying on the shared axes.
TEST(FillRule, FourTrianglesAroundACentreCoverItOnce) {
  const V c{"2.5", "2.5"}, e{"4.9", "2.5"}, s{"2.5", "4.9"}, w{"0.1", "2.5"}, n{"2.5", "0.1"};
  const std::vector<Tri> quads{{c, e, s}, {c, s, w}, {c, w, n}, {c, n, e}};
  for (size_t k = 0; k < quads.size(); ++k) {
    SCOPED_TRACE("quadrant " + std::to_string(k));
    const std::string map = coverage_map({quads[k]}, state(6, 6));
    EXPECT_EQ(map[2 * 7 + 2] == '#', k == 0) << map;  // pixel (2, 2); rows are 7 chars
  }
  EXPECT_EQ(coverage_map(quads, state(6, 6)),
            "..#...\n"
            ".###..\n"
            "#####.\n"
            ".###..\n"
            "..#...\n"
            "......\n");
}

// (0,0) (4,0) (0,4) turns clockwise on screen (y down); (0,0) (0,4) (4,0) counter-
// clockwise. Both cover px + py <= 2 (the hypotenuse through centres with px + py = 3 is
// a right edge): 6 pixels. Which one is culled depends on cull and front_face.
TEST(FillRule, CullModesAndFrontFace) {
  const Tri cw{V{"0", "0"}, V{"4", "0"}, V{"0", "4"}};
  const Tri ccw{V{"0", "0"}, V{"0", "4"}, V{"4", "0"}};
  struct Case { CullMode cull; bool front_ccw; bool cw_drawn, ccw_drawn; SetupOutcome why; };
  for (const Case& k : {Case{CullMode::None, true, true, true, SetupOutcome::Accepted},
                        Case{CullMode::None, false, true, true, SetupOutcome::Accepted},
                        Case{CullMode::Back, true, false, true, SetupOutcome::CulledBackFace},
                        Case{CullMode::Back, false, true, false, SetupOutcome::CulledBackFace},
                        Case{CullMode::Front, true, true, false, SetupOutcome::CulledFrontFace},
                        Case{CullMode::Front, false, false, true, SetupOutcome::CulledFrontFace}}) {
    SCOPED_TRACE("cull " + std::to_string(int(k.cull)) + " front_ccw " + std::to_string(k.front_ccw));
    RasterState st = state(6, 6);
    st.cull = k.cull;
    st.front_ccw = k.front_ccw;
    for (const auto& [tri, drawn, is_ccw] : {std::tuple{cw, k.cw_drawn, false}, std::tuple{ccw, k.ccw_drawn, true}}) {
      SCOPED_TRACE(is_ccw ? "ccw" : "cw");
      std::array<SceneVertex, 3> v{scene_vertex(tri[0]), scene_vertex(tri[1]), scene_vertex(tri[2])};
      SetupTriangle t;
      const SetupOutcome out = setup_triangle(v, st, {"hand", 1}, t);
      EXPECT_EQ(out, drawn ? SetupOutcome::Accepted : k.why);
      if (drawn) {
        EXPECT_EQ(t.ccw_on_screen, is_ccw);
      }
      RenderStats stats;
      const std::string map = coverage_map({tri}, st, &stats);
      EXPECT_EQ(stats.traversal.fragments, drawn ? 6u : 0u);
      EXPECT_EQ(stats.triangles_facing_culled, drawn ? 0u : 1u);
      if (drawn) {
        EXPECT_EQ(map, "###...\n##....\n#.....\n......\n......\n......\n");
      }
    }
  }
}

// Collinear vertices, a repeated vertex, and three vertices that differ in the scene but
// snap to one vertical line (1.000001 is 0.066 LSB of s7.16 from 1): all zero area.
TEST(FillRule, ZeroAreaTrianglesAreCulled) {
  const std::vector<Tri> flat{{V{"0", "0"}, V{"2", "2"}, V{"4.5", "4.5"}},
                              {V{"1.5", "1.5"}, V{"3", "1"}, V{"1.5", "1.5"}},
                              {V{"1", "1"}, V{"1.000001", "3"}, V{"0.9999999", "5"}}};
  for (const Tri& t : flat) {
    std::array<SceneVertex, 3> v{scene_vertex(t[0]), scene_vertex(t[1]), scene_vertex(t[2])};
    SetupTriangle st_out;
    EXPECT_EQ(setup_triangle(v, state(6, 6), {"hand", 1}, st_out), SetupOutcome::CulledZeroArea);
  }
  RenderStats stats;
  coverage_map(flat, state(6, 6), &stats);
  EXPECT_EQ(stats.triangles_in, 3u);
  EXPECT_EQ(stats.triangles_zero_area, 3u);
  EXPECT_EQ(stats.triangles_culled, 3u);
  EXPECT_EQ(stats.traversal.fragments, 0u);
  // Without snapping the third would have had area: the offsets survive in Q64.
  EXPECT_NE(Q64::parse_decimal("1.000001").q, Q64::from_int(1).q);
}

// An 8x6 viewport in a 12x8 framebuffer. A triangle far larger than the viewport covers
// exactly its 48 pixels and nothing of the framebuffer outside it; a scissor of 3x2 at
// (2, 1) leaves 6; a triangle right of the viewport (centres x >= 8.5) is culled as
// outside the clip rectangle.
TEST(FillRule, BoundingBoxIsClippedToViewportAndScissor) {
  RasterState st = state(12, 8);
  const Tri huge{V{"-10", "-10"}, V{"30", "-10"}, V{"-10", "30"}};
  RenderStats stats;
  EXPECT_EQ(coverage_map({huge}, st, &stats, {CmdViewport{8, 6}}),
            "########....\n"
            "########....\n"
            "########....\n"
            "########....\n"
            "########....\n"
            "########....\n"
            "............\n"
            "............\n");
  EXPECT_EQ(stats.traversal.fragments, 48u);
  EXPECT_EQ(coverage_map({huge}, st, &stats, {CmdViewport{8, 6}, CmdScissor{true, 2, 1, 3, 2}}),
            "............\n"
            "..###.......\n"
            "..###.......\n"
            "............\n"
            "............\n"
            "............\n"
            "............\n"
            "............\n");
  EXPECT_EQ(stats.traversal.fragments, 6u);
  coverage_map({{V{"8", "0"}, V{"11", "0"}, V{"8", "3"}}}, st, &stats, {CmdViewport{8, 6}});
  EXPECT_EQ(stats.triangles_outside_clip, 1u);
  EXPECT_EQ(stats.traversal.fragments, 0u);
  // A scissor outside the viewport clips everything.
  coverage_map({huge}, st, &stats, {CmdViewport{8, 6}, CmdScissor{true, 9, 0, 3, 3}});
  EXPECT_EQ(stats.triangles_outside_clip, 1u);
}

// A 127x127 viewport snaps relative to its centre pixel corner (63, 63). The triangle
// (120,120) (127,120) (127,127) sits in the far corner: its top and right edges hold no
// centres and the diagonal x = y is its left edge (the third vertex lies right of it),
// so it covers px >= py for px, py in 120..126: 7 * 8 / 2 = 28 pixels, among them
// (126, 126) at the last column and row.
TEST(FillRule, OddViewportSnapsAroundItsCentre) {
  RasterState st = state(127, 127);
  std::vector<std::pair<int, int>> got;
  Scene scene;
  CmdPrimitives prims;
  for (const V& v : {V{"120", "120"}, V{"127", "120"}, V{"127", "127"}}) prims.vertices.push_back(scene_vertex(v));
  scene.commands.push_back({CmdViewport{127, 127}, {"hand", 1}});
  scene.commands.push_back({std::move(prims), {"hand", 2}});
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) { got.push_back({f.x, f.y}); });
  std::sort(got.begin(), got.end());
  std::vector<std::pair<int, int>> want;
  for (int x = 120; x <= 126; ++x)
    for (int y = 120; y <= x; ++y) want.push_back({x, y});
  EXPECT_EQ(got, want);
  SetupTriangle t;
  ASSERT_EQ(setup_triangle({scene_vertex({"120", "120"}), scene_vertex({"127", "120"}), scene_vertex({"127", "127"})},
                           st, {"hand", 1}, t),
            SetupOutcome::Accepted);
  EXPECT_EQ(t.origin_x, 63);
  EXPECT_EQ(t.x[1], int64_t{64} << 16);  // (127 - 63) px in s7.16
  EXPECT_EQ(t.x[0], int64_t{57} << 16);
}

// s6.8 reaches [-64, 64) px around the origin, so the largest viewport is 126 (origin 63:
// 0 -> -63, 126 -> +63); 127 is refused. In a 126 viewport a vertex at 127 - 1/256 is the
// largest raw value (16383) and 127 is one LSB beyond; -1 is exactly raw_min.
TEST(FillRule, ViewportAndVertexRangeLimits) {
  RasterState st = state(128, 128);
  st.coord_format = FixedFormat{6, 8};
  Framebuffer fb(128, 128);
  RasterState ok = st;
  EXPECT_TRUE(apply_state_command({CmdViewport{126, 126}, {"hand", 1}}, ok, fb));
  EXPECT_EQ(ok.viewport_width, 126);
  RasterState bad = st;
  EXPECT_THROW(apply_state_command({CmdViewport{127, 126}, {"hand", 1}}, bad, fb), SceneError);
  EXPECT_THROW(apply_state_command({CmdViewport{126, 127}, {"hand", 1}}, bad, fb), SceneError);
  ok.out_of_range = OutOfRange::Cull;
  auto outcome = [&](const char* x, const char* y) {
    SetupTriangle t;
    return setup_triangle({scene_vertex({"60", "60"}), scene_vertex({x, y}), scene_vertex({"60", "10"})}, ok,
                          {"hand", 1}, t);
  };
  EXPECT_EQ(outcome("126.99609375", "60"), SetupOutcome::Accepted);
  EXPECT_EQ(outcome("127", "60"), SetupOutcome::CulledOutOfRange);
  EXPECT_EQ(outcome("-1", "60"), SetupOutcome::Accepted);
  EXPECT_EQ(outcome("-1.00390625", "60"), SetupOutcome::CulledOutOfRange);
  // Half an LSB below raw_min is a tie that rounds to the even raw_min; a hair more is out.
  EXPECT_EQ(outcome("30", "-1.001953125"), SetupOutcome::Accepted);
  EXPECT_EQ(outcome("30", "-1.0019531251"), SetupOutcome::CulledOutOfRange);
  ok.out_of_range = OutOfRange::Error;
  EXPECT_THROW(outcome("127", "60"), SceneError);
}

// The state commands are viewport, clear, clear depth and scissor: apply_state_command
// applies them and refuses the drawing commands, and state_commands (a walk's handlers
// for them) takes exactly those four, so a walk without its own primitives and 2D
// handlers does not build.
TEST(FillRule, StateCommandsAreTheFourStateTypes) {
  const auto handlers = state_commands([] { return 1; });
  using H = decltype(handlers);
  static_assert(std::is_invocable_v<H, const CmdViewport&> && std::is_invocable_v<H, const CmdClear&> &&
                std::is_invocable_v<H, const CmdClearDepth&> && std::is_invocable_v<H, const CmdScissor&>);
  static_assert(!std::is_invocable_v<H, const CmdPrimitives&> && !std::is_invocable_v<H, const CmdDraw2d&>);
  EXPECT_EQ(visit_command({CmdClearDepth{}, {"hand", 1}}, Overloaded{handlers, [](const CmdPrimitives&) { return 2; },
                                                                    [](const CmdDraw2d&) { return 3; }}),
            1);
  RasterState st = state(64, 64);
  Framebuffer fb(64, 64);
  EXPECT_TRUE(apply_state_command({CmdScissor{true, 1, 2, 3, 4}, {"hand", 1}}, st, fb));
  EXPECT_TRUE(st.scissor_enabled);
  EXPECT_EQ(st.scissor.x1, 4);
  EXPECT_EQ(st.scissor.y1, 6);
  EXPECT_FALSE(apply_state_command({CmdPrimitives{}, {"hand", 2}}, st, fb));
  EXPECT_FALSE(apply_state_command({CmdDraw2d{}, {"hand", 3}}, st, fb));
}

std::map<std::pair<int, int>, Fragment> render_fragments(const std::vector<Tri>& tris, const RasterState& st) {
  Scene scene;
  CmdPrimitives prims;
  for (const Tri& t : tris)
    for (const V& v : t) prims.vertices.push_back(scene_vertex(v));
  scene.commands.push_back({std::move(prims), {"hand", 1}});
  RenderStats stats;
  std::map<std::pair<int, int>, Fragment> out;
  render_scene(scene, st, stats, [&](const Fragment& f) { out[{f.x, f.y}] = f; });
  return out;
}

// v0 (0,0) red z 0, v1 (8,0) green z 0.5, v2 (0,8) blue z 1, depth 16 bits: z0 = 0,
// z1 = RNE(0.5 * 65535 = 32767.5) = 32768 (even), z2 = 65535. Barycentrics at (x, y):
// w1 = x/8, w2 = y/8, w0 = 1 - w1 - w2; each value rounds half up.
// Pixel (1, 2), centre (1.5, 2.5): w = (1/2, 3/16, 5/16):
//   r = 255/2 = 127.5 -> 128; g = 255*3/16 = 47.8125 -> 48; b = 255*5/16 = 79.6875 -> 80;
//   z = 32768*3/16 + 65535*5/16 = 6144 + 20479.6875 -> 26624.
// Pixel (3, 3), centre (3.5, 3.5): w = (1/8, 7/16, 7/16):
//   r = 31.875 -> 32; g = b = 111.5625 -> 112; z = 14336 + 28671.5625 -> 43008.
// Pixel (0, 0), centre (0.5, 0.5): w = (7/8, 1/16, 1/16):
//   r = 223.125 -> 223; g = b = 15.9375 -> 16; z = 2048 + 4095.9375 -> 6144.
TEST(Interpolation, HandComputedColourAndDepth) {
  RasterState st = state(8, 8);
  st.depth_bits = 16;
  const auto frags = render_fragments(
      {{V{"0", "0", {255, 0, 0}, 0.0}, V{"8", "0", {0, 255, 0}, 0.5}, V{"0", "8", {0, 0, 255}, 1.0}}}, st);
  ASSERT_EQ(frags.size(), 28u);  // px + py <= 6: 7 + 6 + ... + 1
  EXPECT_EQ(frags.at({1, 2}), (Fragment{1, 2, 26624, 128, 48, 80}));
  EXPECT_EQ(frags.at({3, 3}), (Fragment{3, 3, 43008, 32, 112, 112}));
  EXPECT_EQ(frags.at({0, 0}), (Fragment{0, 0, 6144, 223, 16, 16}));
}

// Exact halves round up: red 8 at v1 only, so r = 8 * x / 8 = x at centre x:
// pixel (0, 0) -> 0.5 -> 1, (1, 0) -> 1.5 -> 2, (2, 0) -> 2.5 -> 3 (nearest-even would
// give 0, 2, 2).
TEST(Interpolation, ExactHalvesRoundUp) {
  const auto frags = render_fragments({{V{"0", "0", {0, 0, 0}}, V{"8", "0", {8, 0, 0}}, V{"0", "8", {0, 0, 0}}}},
                                      state(8, 8));
  EXPECT_EQ(frags.at({0, 0}).r, 1);
  EXPECT_EQ(frags.at({1, 0}).r, 2);
  EXPECT_EQ(frags.at({2, 0}).r, 3);
  EXPECT_EQ(frags.at({2, 3}).r, 3);  // depends on x only
}

// With vertices on pixel centres, interpolating at a vertex's own pixel gives that
// vertex's attributes exactly (the other two weights are 0), whether or not the fill
// rule covers it; and every covered pixel's values lie between the vertices' values.
TEST(Interpolation, VertexValuesReproducedAndBounded) {
  const uint64_t seed = 0xf111;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  RasterState st = state(32, 32);
  st.depth_bits = 24;
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    std::array<SceneVertex, 3> v;
    std::array<std::pair<int, int>, 3> pix;
    for (int i = 0; i < 3; ++i) {
      pix[i] = {int(rng() % 32), int(rng() % 32)};
      v[i].x = Q64{(i128(2 * pix[i].first + 1)) << 63};  // px + 1/2
      v[i].y = Q64{(i128(2 * pix[i].second + 1)) << 63};
      v[i].z = double(rng() % 1001) / 1000.0;
      v[i].r = uint8_t(rng());
      v[i].g = uint8_t(rng());
      v[i].b = uint8_t(rng());
    }
    SetupTriangle t;
    if (setup_triangle(v, st, {"gen", n}, t) != SetupOutcome::Accepted) continue;
    ++checked;
    SCOPED_TRACE("triangle " + std::to_string(n));
    for (int i = 0; i < 3; ++i) {
      const Fragment f = interpolate(t, pix[i].first, pix[i].second, 16);
      EXPECT_EQ(f.r, v[i].r);
      EXPECT_EQ(f.g, v[i].g);
      EXPECT_EQ(f.b, v[i].b);
      EXPECT_EQ(f.z, *quantize_unorm(v[i].z, 24));
    }
    TraversalCounters cnt;
    traverse_triangle(t, 8, 16, cnt, [&](int px, int py) {
      const Fragment f = interpolate(t, px, py, 16);
      auto within = [](uint32_t a, uint32_t x, uint32_t y, uint32_t z) {
        return a >= std::min({x, y, z}) && a <= std::max({x, y, z});
      };
      EXPECT_TRUE(within(f.r, v[0].r, v[1].r, v[2].r));
      EXPECT_TRUE(within(f.g, v[0].g, v[1].g, v[2].g));
      EXPECT_TRUE(within(f.b, v[0].b, v[1].b, v[2].b));
      EXPECT_TRUE(within(f.z, t.z[0], t.z[1], t.z[2]));
    });
  }
  EXPECT_GT(checked, 250);
}

// Depth test truth table against a stored depth of 100, written out by hand.
TEST(DepthTest, EveryFuncThroughRopWrite) {
  struct Row { DepthFunc func; bool pass99, pass100, pass101; };
  for (const Row& r : {Row{DepthFunc::Never, false, false, false}, Row{DepthFunc::Less, true, false, false},
                       Row{DepthFunc::LEqual, true, true, false}, Row{DepthFunc::Equal, false, true, false},
                       Row{DepthFunc::Greater, false, false, true}, Row{DepthFunc::GEqual, false, true, true},
                       Row{DepthFunc::NotEqual, true, false, true}, Row{DepthFunc::Always, true, true, true}}) {
    SCOPED_TRACE(to_string(r.func));
    for (bool depth_write : {true, false}) {
      for (const auto& [z, pass] : {std::pair{99u, r.pass99}, {100u, r.pass100}, {101u, r.pass101}}) {
        SCOPED_TRACE("z " + std::to_string(z) + " write " + std::to_string(depth_write));
        Framebuffer fb(2, 1);
        fb.clear_color(1, 2, 3);
        fb.clear_depth(100);
        const Fragment f{1, 0, z, 40, 50, 60};
        EXPECT_EQ(rop_write(fb, f, r.func, depth_write), pass);
        EXPECT_EQ(fb.depth_at(1, 0), pass && depth_write ? z : 100u);
        const uint8_t* p = fb.pixel(1, 0);
        const std::array<uint8_t, 4> rgba{p[0], p[1], p[2], p[3]};
        EXPECT_EQ(rgba, pass ? (std::array<uint8_t, 4>{40, 50, 60, 255}) : (std::array<uint8_t, 4>{1, 2, 3, 255}));
        EXPECT_EQ(fb.depth_at(0, 0), 100u);  // the neighbour is untouched
        EXPECT_EQ(fb.pixel(0, 0)[0], 1);
      }
    }
  }
}

// Two full-viewport squares at depths 0.25 (red) and 0.75 (blue) with depth_func less:
// the near one wins in either drawing order; with greater the far one does.
TEST(DepthTest, NearestWinsInEitherOrder) {
  auto square = [](double z, std::array<uint8_t, 3> rgb) {
    return std::vector<Tri>{{V{"0", "0", rgb, z}, V{"4", "0", rgb, z}, V{"4", "4", rgb, z}},
                            {V{"0", "0", rgb, z}, V{"4", "4", rgb, z}, V{"0", "4", rgb, z}}};
  };
  const auto near = square(0.25, {255, 0, 0}), far = square(0.75, {0, 0, 255});
  for (DepthFunc func : {DepthFunc::Less, DepthFunc::Greater}) {
    for (bool near_first : {true, false}) {
      SCOPED_TRACE(std::string(to_string(func)) + (near_first ? " near first" : " far first"));
      RasterState st = state(4, 4);
      st.depth_func = func;
      Scene scene;
      if (func == DepthFunc::Greater) scene.commands.push_back({CmdClearDepth{0.0}, {"hand", 1}});
      for (const auto* group : near_first ? std::array{&near, &far} : std::array{&far, &near}) {
        CmdPrimitives prims;
        for (const Tri& t : *group)
          for (const V& v : t) prims.vertices.push_back(scene_vertex(v));
        scene.commands.push_back({std::move(prims), {"hand", 2}});
      }
      RenderStats stats;
      const Framebuffer fb = render_scene(scene, st, stats);
      const uint8_t want_r = func == DepthFunc::Less ? 255 : 0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(fb.pixel(x, y)[0], want_r) << x << "," << y;
      EXPECT_EQ(stats.traversal.fragments, 32u);
      // The first group always passes (16); the second passes only when it is the winner.
      const bool second_wins = (func == DepthFunc::Less) != near_first;
      EXPECT_EQ(stats.fragments_passed, second_wins ? 32u : 16u);
    }
  }
}

}  // namespace
}  // namespace rastsim
