// SPDX-License-Identifier: Apache-2.0
// Clip-space trace input (docs/trace-format.md, "Clip-space input"): tri4 in its three
// forms, v4 in every block, the front-end state each command carries, binary32 rounding
// of decimal text (expected bit patterns worked by hand from IEEE 754, never from the
// parser), and every malformed line rejected with "file:line: what".
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>

#include "scene_test.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;

Scene parse(const std::string& text) { return parse_trace(text, "c.trace"); }

const CmdPrimitives& prims(const Scene& s, size_t i) { return std::get<CmdPrimitives>(s.commands.at(i).body); }

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

// The one vertex of `v4 X 0 0 1` in a points block: how the token X reads.
float read_x(const std::string& tok) {
  return prims(parse("points\nv4 " + tok + " 0 0 1\nend\n"), 0).clip_vertices.at(0).x;
}

void expect_vertex(const ClipVertex& v, float x, float y, float z, float w) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
  EXPECT_EQ(v.w, w);
}

void expect_rgbst(const ClipVertex& v, int r, int g, int b, float s, float t) {
  EXPECT_EQ(v.r, r);
  EXPECT_EQ(v.g, g);
  EXPECT_EQ(v.b, b);
  EXPECT_EQ(v.s, s);
  EXPECT_EQ(v.t, t);
}

TEST(SceneClip, Tri4TakesTheCurrentColourAndTexcoord) {
  const Scene s = parse(
      "color 10 20 30\n"
      "texcoord 0.25 -2\n"
      "tri4 0 0 0 1  1 0 0.5 2  0 -1 1 4\n");
  ASSERT_EQ(s.commands.size(), 1u);
  const CmdPrimitives& p = prims(s, 0);
  EXPECT_EQ(s.commands[0].loc.line, 3);
  EXPECT_EQ(p.topology, Topology::List);
  EXPECT_TRUE(p.vertices.empty());
  ASSERT_EQ(p.clip_vertices.size(), 3u);
  expect_vertex(p.clip_vertices[0], 0, 0, 0, 1);
  expect_vertex(p.clip_vertices[1], 1, 0, 0.5f, 2);
  expect_vertex(p.clip_vertices[2], 0, -1, 1, 4);
  for (const ClipVertex& v : p.clip_vertices) expect_rgbst(v, 10, 20, 30, 0.25f, -2.0f);
  EXPECT_EQ(p.clip, ClipState{});  // the defaults: whole viewport, depth 0..1, 1-pixel points, no sprite
}

TEST(SceneClip, Tri4WithColoursAndTexcoords) {
  const Scene s = parse(
      "texcoord 9 9\n"
      "tri4 1 2 3 4 5 6 7  8 9 10 11 12 13 14  -1 -2 -3 -4 255 0 1\n"
      "tri4 1 2 3 4 5 6 7 0.5 0.75  8 9 10 11 12 13 14 1 2  -1 -2 -3 -4 255 0 1 -0.5 1e3\n");
  const CmdPrimitives& a = prims(s, 0);
  expect_vertex(a.clip_vertices[1], 8, 9, 10, 11);
  expect_rgbst(a.clip_vertices[0], 5, 6, 7, 9, 9);
  expect_rgbst(a.clip_vertices[2], 255, 0, 1, 9, 9);
  const CmdPrimitives& b = prims(s, 1);
  expect_vertex(b.clip_vertices[2], -1, -2, -3, -4);
  expect_rgbst(b.clip_vertices[0], 5, 6, 7, 0.5f, 0.75f);
  expect_rgbst(b.clip_vertices[1], 12, 13, 14, 1, 2);
  expect_rgbst(b.clip_vertices[2], 255, 0, 1, -0.5f, 1000);
}

// Decimal text to binary32 with one round to nearest even, worked from IEEE 754:
// 2^24 + 1 lies halfway between 2^24 and 2^24 + 2 (spacing 2 there) and ties to the even
// significand, 2^24; 2^24 + 3 ties to 2^24 + 4. 0.1 is 0x3DCCCCCD (significand
// 0x4CCCCD, the 0.1 of every C compiler's 0.1f). The smallest denormal is 2^-149 (about
// 1.4013e-45): 1e-45 is nearest to it, 1e-46 is below half of it and rounds to 0.
TEST(SceneClip, NumbersAreBinary32RoundedOnceToNearestEven) {
  EXPECT_EQ(bits(read_x("16777217")), 0x4B800000u);  // 2^24
  EXPECT_EQ(bits(read_x("16777219")), 0x4B800002u);  // 2^24 + 4
  EXPECT_EQ(bits(read_x("16777218")), 0x4B800001u);  // exact
  EXPECT_EQ(bits(read_x("0.1")), 0x3DCCCCCDu);
  EXPECT_EQ(bits(read_x("-0.1")), 0xBDCCCCCDu);
  EXPECT_EQ(bits(read_x("1e-45")), 0x00000001u);
  EXPECT_EQ(bits(read_x("1e-46")), 0x00000000u);
  EXPECT_EQ(bits(read_x("-1e-46")), 0x80000000u);  // the sign survives underflow
  EXPECT_EQ(bits(read_x("1e-99999")), 0x00000000u);
  // 2^-150 (half the smallest denormal) is 7.00649232162408535...e-46: just below it
  // rounds to 0, just above it to 2^-149.
  EXPECT_EQ(bits(read_x("7.006492321624085e-46")), 0x00000000u);
  EXPECT_EQ(bits(read_x("7.0064923216240862e-46")), 0x00000001u);
  EXPECT_EQ(bits(read_x("1.17549435e-38")), 0x00800000u);  // 2^-126, the smallest normal
  // The largest binary32, (2 - 2^-23) 2^127 = 340282346638528859811704183484516925440.
  EXPECT_EQ(bits(read_x("3.4028235e38")), 0x7F7FFFFFu);
  EXPECT_EQ(bits(read_x("340282356779733661637539395458142568447")), 0x7F7FFFFFu);  // below the halfway point
  EXPECT_EQ(bits(read_x("+2.5")), 0x40200000u);
  EXPECT_EQ(bits(read_x("-.5e+1")), 0xC0A00000u);
  EXPECT_EQ(bits(read_x("-0")), 0x80000000u);
  EXPECT_EQ(bits(read_x("7.")), 0x40E00000u);
}

TEST(SceneClip, NumbersBeyondBinary32OrNotFiniteAreErrors) {
  auto bad = [](const std::string& tok, const std::string& phrase) {
    return SceneFails([&] { parse("points\nv4 1 2 3 " + tok + "\nend\n"); }, "c.trace:2:", "w '" + tok + "' " + phrase);
  };
  EXPECT_TRUE(bad("3.5e38", "is outside the binary32 range"));
  EXPECT_TRUE(bad("-3.5e38", "is outside the binary32 range"));
  // 2^128 - 2^103: halfway between the largest binary32 and 2^128, ties to 2^128.
  EXPECT_TRUE(bad("340282356779733661637539395458142568448", "is outside the binary32 range"));
  EXPECT_TRUE(bad("1e99999", "is outside the binary32 range"));
  EXPECT_TRUE(bad("inf", "is not finite"));
  EXPECT_TRUE(bad("-infinity", "is not finite"));
  EXPECT_TRUE(bad("nan", "is not finite"));
  for (const char* tok : {"1e", "0x10", "+-1", "--1", "1..2", "1,5", "e5", ".", "+", "1f", "12px"})
    EXPECT_TRUE(bad(tok, "is not a decimal number")) << tok;
}

TEST(SceneClip, V4BlocksGiveClipSpaceCommandsOfEveryTopology) {
  const Scene s = parse(
      "strip\nv4 0 0 0 1\nv4 1 0 0 1\nv4 0 1 0 1\nend\n"
      "fan\nv4 0 0 0 1\nv4 1 0 0 1\nv4 0 1 0 1\nv4 -1 0 0 1\nend\n"
      "lines\nv4 0 0 0 1\nv4 1 0 0 1\nend\n"
      "linestrip\nv4 0 0 0 1\nv4 1 0 0 1\nend\n"
      "lineloop\nv4 0 0 0 1\nv4 1 0 0 1\nv4 1 1 0 1\nend\n"
      "points\nv4 0.5 0.5 0.5 1\nend\n");
  const Topology want[] = {Topology::Strip, Topology::Fan, Topology::Lines, Topology::LineStrip, Topology::LineLoop,
                           Topology::Points};
  const size_t count[] = {3, 4, 2, 2, 3, 1};
  const int line[] = {2, 7, 13, 17, 21, 26};  // each command is named by its first v4
  ASSERT_EQ(s.commands.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(prims(s, i).topology, want[i]);
    EXPECT_EQ(prims(s, i).clip_vertices.size(), count[i]);
    EXPECT_TRUE(prims(s, i).vertices.empty());
    EXPECT_EQ(s.commands[i].loc.line, line[i]);
  }
}

// Quads (a, b, c, d) -> (a, b, c), (a, c, d); quad strip quad k (v2k, v2k+1, v2k+3,
// v2k+2), as for `v` blocks: vertex i has x = i to tell them apart.
TEST(SceneClip, V4QuadsSplitAsVBlocksDo) {
  const Scene s = parse(
      "quads\nv4 0 0 0 1\nv4 1 0 0 1\nv4 2 0 0 1\nv4 3 0 0 1\nend\n"
      "quadstrip\nv4 0 0 0 1\nv4 1 0 0 1\nv4 2 0 0 1\nv4 3 0 0 1\nv4 4 0 0 1\nv4 5 0 0 1\nend\n");
  auto xs = [&](size_t i) {
    std::vector<float> x;
    for (const ClipVertex& v : prims(s, i).clip_vertices) x.push_back(v.x);
    return x;
  };
  EXPECT_EQ(prims(s, 0).topology, Topology::List);
  EXPECT_EQ(xs(0), (std::vector<float>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(xs(1), (std::vector<float>{0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}));
}

TEST(SceneClip, V4FormsTakeStateOrTheirOwnAttributes) {
  const Scene s = parse(
      "color 1 2 3\ntexcoord 4 5\n"
      "points\nv4 0 0 0 1\nv4 0 0 0 1 7 8 9\nv4 0 0 0 1 7 8 9 0.125 -1\n"
      "color 11 12 13\ntexcoord 14 15\nv4 0 0 0 1\nend\n");
  const CmdPrimitives& p = prims(s, 0);
  ASSERT_EQ(p.clip_vertices.size(), 4u);
  expect_rgbst(p.clip_vertices[0], 1, 2, 3, 4, 5);
  expect_rgbst(p.clip_vertices[1], 7, 8, 9, 4, 5);
  expect_rgbst(p.clip_vertices[2], 7, 8, 9, 0.125f, -1);
  expect_rgbst(p.clip_vertices[3], 11, 12, 13, 14, 15);  // colour and texcoord change inside a block
}

TEST(SceneClip, TwoDimensionalBlocksStayTwoDimensional) {
  const Scene s = parse("lines\nv 0 0\nv 1 1\nend\nlinestrip\nv 0 0\nv 1 1\nend\nlineloop\nv 0 0\nv 1 1\nend\n");
  for (size_t i = 0; i < 3; ++i) EXPECT_TRUE(std::holds_alternative<CmdDraw2d>(s.commands.at(i).body)) << i;
}

TEST(SceneClip, TexcoordReachesScreenSpaceVertices) {
  const Scene s = parse("texcoord 0.5 -0.25\ntri 0 0 1 0 0 1\nstrip\nv 0 0\nv 1 0 0 1 2 3\nv 0 1\nend\n");
  for (size_t i = 0; i < 2; ++i)
    for (const SceneVertex& v : prims(s, i).vertices) {
      EXPECT_EQ(v.s, 0.5f);
      EXPECT_EQ(v.t, -0.25f);
      EXPECT_EQ(v.inv_w, 1.0f);
    }
  // Without a texcoord line a vertex's is (0, 0).
  const SceneVertex v = prims(parse("tri 0 0 1 0 0 1\n"), 0).vertices[0];
  EXPECT_EQ(v.s, 0.0f);
  EXPECT_EQ(v.t, 0.0f);
}

TEST(SceneClip, FrontEndStateTravelsWithEachCommand) {
  const Scene s = parse(
      "viewport_xform 10 -20 300 200\n"
      "depth_range 0.25 0.1\n"  // reversed ranges are allowed, as glDepthRange allows them
      "point_size 7\n"
      "point_sprite on\n"
      "tri4 0 0 0 1 1 0 0 1 0 1 0 1\n"
      "viewport_xform default\n"
      "depth_range 0 1\n"
      "point_sprite off\n"
      "points\nv4 0 0 0 1\npoint_size 3\nend\n");  // a block takes the state at its end
  const ClipState& a = prims(s, 0).clip;
  EXPECT_EQ(a.xform, (ViewportXform{false, 10, -20, 300, 200}));
  EXPECT_EQ(a.depth_near, 0.25f);
  EXPECT_EQ(a.depth_far, 0.1f);
  EXPECT_EQ(a.point_size, 7.0f);
  EXPECT_TRUE(a.point_sprite);
  const ClipState& b = prims(s, 1).clip;
  EXPECT_TRUE(b.xform.whole_viewport);
  EXPECT_EQ(b.depth_near, 0.0f);
  EXPECT_EQ(b.depth_far, 1.0f);
  EXPECT_EQ(b.point_size, 3.0f);
  EXPECT_FALSE(b.point_sprite);
}

TEST(SceneClip, StateOnlyTracesStillNeedADraw) {
  EXPECT_TRUE(SceneFails([] { parse("texcoord 0 0\nviewport_xform 0 0 8 8\n"); }, "c.trace:", "tri4 or points"));
}

struct BadLine {
  const char* text;
  int line;
  const char* phrase;
};

TEST(SceneClip, MalformedLinesNameTheirLine) {
  const BadLine cases[] = {
      {"tri4 0 0 0 1 0 0 0 1 0 0 0\n", 1,
       "'tri4' takes 12 numbers (x y z w per vertex), 21 (x y z w r g b per vertex) or 27 (x y z w r g b s t per "
       "vertex), got 11"},
      {"tri4 0 0 0 1 0 0 0 1 0 0 0 1 5\n", 1, "got 13"},
      {"tri4 0 0 0 1 0 0 0 1 0 0 nan 1\n", 1, "vertex 2 z 'nan' is not finite"},
      {"tri4 0 0 0 1 0 0 0 1 0 0 0 1e39\n", 1, "vertex 2 w '1e39' is outside the binary32 range"},
      {"tri4 0 0 0 1 0 0 0  0 0 0 1 256 0 0  0 0 0 1 0 0 0\n", 1, "vertex 1 red 256 is outside 0..255"},
      {"tri4 0 0 0 1 0 0 0 0 0  0 0 0 1 0 0 0 0 0  0 0 0 1 0 0 0 0 inf\n", 1, "vertex 2 t 'inf' is not finite"},
      {"\nstrip\nv4 0 0 0\nend\n", 3, "'v4' takes 4 numbers (x y z w), 7 (x y z w r g b) or 9 (x y z w r g b s t), got 3"},
      {"points\nv4 0 0 0 1 1 2 3 4\nend\n", 2, "got 8"},
      {"points\nv4 0 0 0 1 1 2 x\nend\n", 2, "blue 'x' is not an integer"},
      {"points\nv4 0 0 0 1 1 2 3 0 nan\nend\n", 2, "t 'nan' is not finite"},
      {"v4 0 0 0 1\n", 1, "'v4' outside a block"},
      {"polygon\nv4 0 0 0 1\n", 2, "'v4' in a 'polygon'"},
      {"points\nv 0 0\nend\n", 2, "'v' in a 'points' block"},
      {"strip\nv 0 0\nv4 0 0 0 1\n", 3, "'v4' in the 'strip' begun at line 1, whose vertices are 'v': a block's "
                                        "vertices are all 'v' or all 'v4'"},
      {"lines\nv4 0 0 0 1\nv 0 0\n", 3, "'v' in the 'lines' begun at line 1, whose vertices are 'v4'"},
      {"points\nend\n", 1, "'points' has 0 vertices; it needs at least 1"},
      {"\nlines\nv4 0 0 0 1\nend\n", 2, "'lines' has 1 vertices; it needs an even number"},
      {"fan\nv4 0 0 0 1\nv4 0 0 0 1\nend\n", 1, "'fan' has 2 vertices; it needs at least 3"},
      {"quads\nv4 0 0 0 1\nv4 0 0 0 1\nv4 0 0 0 1\nend\n", 1, "'quads' has 3 vertices"},
      {"points\nv4 0 0 0 1\n", 1, "'points' without 'end'"},
      {"texcoord 1\n", 1, "'texcoord' takes 2 arguments (s t, binary32 repeats), got 1"},
      {"texcoord 1 -inf\n", 1, "texcoord t '-inf' is not finite"},
      {"texcoord 1e40 0\n", 1, "texcoord s '1e40' is outside the binary32 range"},
      {"viewport_xform 0 0 0 8\n", 1, "viewport_xform width 0 is outside 1..16384"},
      {"viewport_xform 0 0 8 16385\n", 1, "viewport_xform height 16385 is outside 1..16384"},
      {"viewport_xform -16385 0 8 8\n", 1, "viewport_xform x -16385 is outside -16384..16384"},
      {"viewport_xform 0 0.5 8 8\n", 1, "viewport_xform y '0.5' is not an integer"},
      {"viewport_xform 0 0 8\n", 1, "'viewport_xform' takes 4 arguments (X Y W H, integers, W and H 1..16384; or "
                                    "'default')"},
      {"viewport_xform defaults\n", 1, "'viewport_xform' takes 4 arguments"},
      {"depth_range 0 1.5\n", 1, "depth_range far '1.5' is outside [0, 1]"},
      {"depth_range -0.1 1\n", 1, "depth_range near '-0.1' is outside [0, 1]"},
      {"depth_range 0 nan\n", 1, "depth_range far 'nan' is not finite"},
      {"depth_range 0\n", 1, "'depth_range' takes 2 arguments (N F, each in [0, 1]), got 1"},
      {"point_sprite yes\n", 1, "point_sprite 'yes' is not 'on' or 'off'"},
      {"point_sprite\n", 1, "'point_sprite' takes 1 argument"},
      {"strip\nv4 0 0 0 1\nviewport_xform 0 0 8 8\n", 3, "'viewport_xform' inside the 'strip' begun at line 1"},
      {"points\nv4 0 0 0 1\ndepth_range 0 1\n", 3, "'depth_range' inside the 'points' begun at line 1"},
      {"lines\npoint_sprite on\n", 2, "'point_sprite' inside the 'lines' begun at line 1"},
      {"strip\ntri4 0 0 0 1 0 0 0 1 0 0 0 1\n", 2, "'tri4' inside the 'strip'"},
      {"strip\npoints\n", 2, "'points' inside the 'strip'"},
  };
  for (const BadLine& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_TRUE(SceneFails([&] { parse(c.text); }, "c.trace:" + std::to_string(c.line) + ":", c.phrase));
  }
}

// The example scene (docs/trace-format.md): a perspective cube the near plane cuts, with
// colours and texture coordinates; every vertex binary32 as written.
TEST(SceneClip, ClipCubeExampleParses) {
  const Scene s = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/traces/3d/clip_cube.trace");
  size_t triangles = 0, behind_near = 0, textured = 0;
  for (const Command& c : s.commands) {
    const auto* p = std::get_if<CmdPrimitives>(&c.body);
    if (!p) continue;
    ASSERT_TRUE(p->clip_space()) << c.loc.str();
    triangles += p->topology == Topology::List ? p->clip_vertices.size() / 3 : p->clip_vertices.size() - 2;
    for (const ClipVertex& v : p->clip_vertices) {
      behind_near += v.z < 0;  // z < 0: in front of the near plane's cut, clipped away
      textured += v.s != 0 || v.t != 0;
    }
  }
  EXPECT_EQ(triangles, 12u);  // six faces of two triangles
  EXPECT_GT(behind_near, 0u);
  EXPECT_GT(textured, 0u);
}

}  // namespace
}  // namespace rastsim
