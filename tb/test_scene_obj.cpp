// SPDX-License-Identifier: Apache-2.0
// OBJ loader tests: placement maths on meshes whose screen positions are worked by hand,
// index forms and relative indices, materials and shading, winding on screen, and every
// malformed input rejected with "file:line: what".
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "scene_test.h"
#include "ref/pipeline.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "config/raster_state_config.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;

const std::string kData = RASTSIM_TEST_DATA;

// Head-on, no rotation, 100x100, sphere spans the viewport: one object unit is
// 50 / R pixels.
ObjPlacement flat(int w = 100, int h = 100, double fill = 1.0) {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.viewport_width = w;
  p.viewport_height = h;
  p.yaw_deg = 0;
  p.pitch_deg = 0;
  p.fill = fill;
  return p;
}

Scene parse(const std::string& text, const ObjPlacement& p = obj_placement_from_config(Config{})) {
  return parse_obj(text, "m.obj", p, kData);
}

const CmdPrimitives& face(const Scene& s, size_t i) { return std::get<CmdPrimitives>(s.commands.at(2 + i).body); }

double area2(const SceneVertex& a, const SceneVertex& b, const SceneVertex& c) {
  return (b.x.to_double() - a.x.to_double()) * (c.y.to_double() - a.y.to_double()) -
         (b.y.to_double() - a.y.to_double()) * (c.x.to_double() - a.x.to_double());
}

using scene_test::kOcta;

TEST(SceneObj, HeadOnPlacementIsExact) {
  const Scene s = parse(kOcta, flat());
  ASSERT_EQ(s.commands.size(), 4u);
  EXPECT_EQ(s.source, "m.obj");
  const auto& clear = std::get<CmdClear>(s.commands[0].body);
  EXPECT_EQ(clear.r, 0);
  EXPECT_EQ(std::get<CmdClearDepth>(s.commands[1].body).z, 1.0);
  EXPECT_EQ(s.commands[2].loc.line, 7);
  EXPECT_EQ(s.commands[3].loc.line, 8);
  // 10 px per unit, centre (50, 50), y up: (5,0,0) -> (100, 50); (0,5,0) -> (50, 0);
  // (0,0,5) -> (50, 50) at depth 0 (nearest), (0,0,-5) at depth 1.
  const auto& f = face(s, 0);
  EXPECT_EQ(f.topology, Topology::List);
  ASSERT_EQ(f.vertices.size(), 3u);
  EXPECT_EQ(f.vertices[0].x.q, Q64::from_int(100).q);
  EXPECT_EQ(f.vertices[0].y.q, Q64::from_int(50).q);
  EXPECT_EQ(f.vertices[0].z, 0.5);
  EXPECT_EQ(f.vertices[1].x.q, Q64::from_int(50).q);
  EXPECT_EQ(f.vertices[1].y.q, Q64::from_int(0).q);
  EXPECT_EQ(f.vertices[2].x.q, Q64::from_int(50).q);
  EXPECT_EQ(f.vertices[2].y.q, Q64::from_int(50).q);
  EXPECT_EQ(f.vertices[2].z, 0.0);
  const auto& g = face(s, 1);
  EXPECT_EQ(g.vertices[0].x.q, Q64::from_int(0).q);   // (-5,0,0)
  EXPECT_EQ(g.vertices[1].z, 1.0);                     // (0,0,-5)
  EXPECT_EQ(g.vertices[2].y.q, Q64::from_int(100).q);  // (0,-5,0)
}

TEST(SceneObj, NonSquareViewportAndFill) {
  // s = fill * min(W, H) / 2 = 0.5 * 100 / 2 = 25 px per radius: (5,0,0) -> (125, 50).
  const Scene s = parse(kOcta, flat(200, 100, 0.5));
  EXPECT_EQ(face(s, 0).vertices[0].x.q, Q64::from_int(125).q);
  EXPECT_EQ(face(s, 0).vertices[0].y.q, Q64::from_int(50).q);
  EXPECT_EQ(face(s, 0).vertices[1].y.q, Q64::from_int(25).q);
}

TEST(SceneObj, OffCentreMeshIsCentred) {
  // Bounding box [10, 14] x [20, 23] x [0, 0]: centre (12, 21.5, 0); farthest corner at
  // distance 2.5, so 20 px per unit. (10, 20) -> (50 - 40, 50 + 30) = (10, 80).
  const Scene s = parse("v 10 20 0\nv 14 20 0\nv 14 23 0\nv 99 99 99\nf 1 2 3\n", flat());
  const auto& v = face(s, 0).vertices;
  EXPECT_NEAR(v[0].x.to_double(), 10, 1e-9);
  EXPECT_NEAR(v[0].y.to_double(), 80, 1e-9);
  EXPECT_NEAR(v[2].x.to_double(), 90, 1e-9);
  EXPECT_NEAR(v[2].y.to_double(), 20, 1e-9);
  EXPECT_NEAR(v[0].z, 0.5, 1e-12);
}

TEST(SceneObj, YawAndPitchTurnTheModel) {
  ObjPlacement p = flat();
  p.yaw_deg = 90;  // +z turns toward +x; +x turns away from the viewer
  Scene s = parse(kOcta, p);
  EXPECT_NEAR(face(s, 0).vertices[0].z, 1.0, 1e-12);              // (5,0,0): far
  EXPECT_NEAR(face(s, 0).vertices[0].x.to_double(), 50, 1e-9);
  EXPECT_NEAR(face(s, 0).vertices[2].x.to_double(), 100, 1e-9);   // (0,0,5): right
  EXPECT_NEAR(face(s, 0).vertices[2].z, 0.5, 1e-12);
  p.yaw_deg = 0;
  p.pitch_deg = 90;  // +y turns toward the viewer
  s = parse(kOcta, p);
  EXPECT_NEAR(face(s, 0).vertices[1].z, 0.0, 1e-12);              // (0,5,0): near
  EXPECT_NEAR(face(s, 0).vertices[1].y.to_double(), 50, 1e-9);
  EXPECT_NEAR(face(s, 0).vertices[2].y.to_double(), 100, 1e-9);   // (0,0,5): down
}

TEST(SceneObj, IndexFormsAndRelativeIndices) {
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0 0\nvn 0 0 1\n";
  const Scene a = parse(verts + "f 1 2 3\nf 1/1 3/2 4/1\nf 1//1 2//1 4//1\nf 2/2/1 3/1/1 4/2/1\n", flat());
  const Scene b = parse(verts + "f -4 -3 -2\nf -4/-2 -2/-1 -1/-2\nf -4//-1 -3//1 -1//1\nf -3/-1/-1 -2/-2/-1 -1/2/1\n", flat());
  ASSERT_EQ(a.commands.size(), 6u);
  ASSERT_EQ(b.commands.size(), 6u);
  for (size_t i = 0; i < 4; ++i)
    for (size_t k = 0; k < 3; ++k) {
      SCOPED_TRACE("face " + std::to_string(i) + " corner " + std::to_string(k));
      EXPECT_EQ(face(a, i).vertices[k].x.q, face(b, i).vertices[k].x.q);
      EXPECT_EQ(face(a, i).vertices[k].y.q, face(b, i).vertices[k].y.q);
    }
  // Relative indices count back from the vertices defined so far, not from the end.
  const Scene c = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 0\nf -4 -3 -2\n", flat());
  EXPECT_EQ(face(c, 0).vertices[1].x.q, face(c, 1).vertices[1].x.q);
}

TEST(SceneObj, PolygonsAreFannedFromTheFirstCorner) {
  const Scene s = parse("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv -2 0 0\nf 1 2 3 4 5\n", flat());
  const auto& v = face(s, 0).vertices;
  ASSERT_EQ(v.size(), 9u);  // (0,1,2) (0,2,3) (0,3,4)
  const int corner[9] = {0, 1, 2, 0, 2, 3, 0, 3, 4};
  const Scene single = parse("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv -2 0 0\nf 1 2 3\nf 4 5 1\n", flat());
  // Corner positions from the single-corner faces: 1 2 3 come from face 0, 4 5 from face 1.
  const SceneVertex pos[5] = {face(single, 0).vertices[0], face(single, 0).vertices[1],
                              face(single, 0).vertices[2], face(single, 1).vertices[0],
                              face(single, 1).vertices[1]};
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(v[i].x.q, pos[corner[i]].x.q) << i;
    EXPECT_EQ(v[i].y.q, pos[corner[i]].y.q) << i;
  }
}

TEST(SceneObj, WindingIsKeptOnScreen) {
  // CCW seen from +z (front-facing) must be CCW on screen: doubled y-down area < 0.
  for (const ObjPlacement& p : {flat(), obj_placement_from_config(Config{})}) {
    const Scene s = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n", p);
    const auto& front = face(s, 0).vertices;
    const auto& back = face(s, 1).vertices;
    EXPECT_LT(area2(front[0], front[1], front[2]), 0);
    EXPECT_GT(area2(back[0], back[1], back[2]), 0);
  }
}

TEST(SceneObj, ColoursAndHeadlightShading) {
  const std::string text =
      "mtllib cube.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "v 0 0 0 0.2 0.4 0.6\nv 1 0 0 0.2 0.4 0.6\nv 0 1 0 0.2 0.4 0.6\n"
      "v 0 0.5 -0.8660254037844386\n"
      "f 1 2 3\n"   // head-on, no material: white, shade 1
      "f 1 3 2\n"   // turned away: ambient 0.25 -> round(63.75) = 64
      "f 1 2 7\n"   // n_z = cos 60 = 0.5: shade 0.625 -> round(159.375) = 159
      "usemtl blue\n"
      "f 1 2 3\n"   // Kd 0 0.2 1 head-on: (0, 51, 255)
      "f 4 5 6\n";  // vertex colours beat the material: (51, 102, 153)
  const Scene s = parse(text, flat());
  auto rgb = [&](size_t f) {
    const SceneVertex& v = face(s, f).vertices[0];
    return std::array<int, 3>{v.r, v.g, v.b};
  };
  EXPECT_EQ(rgb(0), (std::array<int, 3>{255, 255, 255}));
  EXPECT_EQ(rgb(1), (std::array<int, 3>{64, 64, 64}));
  EXPECT_EQ(rgb(2), (std::array<int, 3>{159, 159, 159}));
  EXPECT_EQ(rgb(3), (std::array<int, 3>{0, 51, 255}));
  EXPECT_EQ(rgb(4), (std::array<int, 3>{51, 102, 153}));
}

TEST(SceneObj, KdRoundsHalfUp) {
  // 0.5 * 255 = 127.5 exactly: rounds up to 128. One grey value sets all channels.
  const std::string dir = kData;
  const Scene s = parse_obj("mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n", "m.obj", flat(), dir);
  EXPECT_EQ(face(s, 0).vertices[0].r, 255);
  EXPECT_EQ(face(s, 0).vertices[0].g, 0);
  const Scene h = parse("v 0 0 0 0.5 0.5 +5e-1\nv 1 0 0\nv 0 1 0\nf +1 2 3\n", flat());
  EXPECT_EQ(face(h, 0).vertices[0].r, 128);
  EXPECT_EQ(face(h, 0).vertices[0].b, 128);  // '+' signs and exponents are accepted
}

// cube.obj: every index form, two materials; default placement yaw 30, pitch 20.
TEST(SceneObj, CubeFileLoadsWithMaterials) {
  const Scene s = load_obj(kData + "/cube.obj", obj_placement_from_config(Config{}));
  ASSERT_EQ(s.commands.size(), 8u);
  EXPECT_EQ(s.source, kData + "/cube.obj");
  // Shade 0.25 + 0.75 n_z with n_z of each face after the rotation:
  // front cos30 cos20 = 0.8138 -> 219; back/right/bottom face away -> 0.25;
  // left sin30 cos20 = 0.4698 -> shade 0.6024; top sin20 = 0.3420 -> shade 0.5065.
  const int expect[6][3] = {
      {219, 219, 219},  // front, white
      {64, 0, 0},       // back, red
      {64, 0, 0},       // right, red
      {0, 31, 154},     // left, blue (0, 0.2, 1)
      {0, 26, 129},     // top, blue
      {0, 13, 64},      // bottom, blue: 12.75 -> 13
  };
  const int lines[6] = {22, 25, 27, 30, 32, 35};
  for (size_t f = 0; f < 6; ++f) {
    SCOPED_TRACE("face " + std::to_string(f));
    EXPECT_EQ(s.commands[2 + f].loc.line, lines[f]);
    const auto& v = face(s, f).vertices;
    ASSERT_EQ(v.size(), 6u);
    EXPECT_EQ(v[0].r, expect[f][0]);
    EXPECT_EQ(v[0].g, expect[f][1]);
    EXPECT_EQ(v[0].b, expect[f][2]);
    // Visible faces (shade above ambient) are counter-clockwise on screen.
    const bool visible = f == 0 || f == 3 || f == 4;
    EXPECT_EQ(area2(v[0], v[1], v[2]) < 0, visible);
    EXPECT_EQ(area2(v[3], v[4], v[5]) < 0, visible);
  }
}

TEST(SceneObj, CubeRendersWithBackFaceCulling) {
  const Scene s = load_obj(kData + "/cube.obj", obj_placement_from_config(Config{}));
  RasterState st = raster_state_from_config(Config{});
  st.cull = CullMode::Back;
  st.depth_func = DepthFunc::Less;
  RenderStats stats;
  render_scene(s, st, stats);
  EXPECT_EQ(stats.triangles_in, 12u);
  EXPECT_EQ(stats.triangles_facing_culled, 6u);  // the three faces turned away
  EXPECT_EQ(stats.triangles_rasterized, 6u);
  EXPECT_GT(stats.fragments_passed, 0u);
}

TEST(SceneObj, LoadMissingFile) {
  try {
    load_obj(kData + "/nope.obj", obj_placement_from_config(Config{}));
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), kData + "/nope.obj: cannot open");
  }
}

TEST(SceneObj, BadPlacement) {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.fill = 0;
  EXPECT_TRUE(SceneFails([&] { parse(kOcta, p); }, "m.obj:", "OBJ placement"));
  p = obj_placement_from_config(Config{});
  p.viewport_height = 0;
  EXPECT_TRUE(SceneFails([&] { parse(kOcta, p); }, "m.obj:", "OBJ placement"));
  p = obj_placement_from_config(Config{});
  p.yaw_deg = NAN;
  EXPECT_TRUE(SceneFails([&] { parse(kOcta, p); }, "m.obj:", "OBJ placement"));
}

TEST(SceneObj, DegenerateMeshesStayFinite) {
  // All corners on one point: R = 0 is treated as 1; everything lands on the centre.
  const Scene s = parse("v 3 3 3\nv 3 3 3\nv 3 3 3\nf 1 2 3\n", flat());
  EXPECT_EQ(face(s, 0).vertices[0].x.q, Q64::from_int(50).q);
  EXPECT_EQ(face(s, 0).vertices[0].z, 0.5);
  // Extreme but finite coordinates are placed, not overflowed.
  const Scene h = parse("v -1e308 0 0\nv 1e308 0 0\nv 0 1e-300 0\nf 1 2 3\n", flat());
  EXPECT_NEAR(face(h, 0).vertices[0].x.to_double(), 0, 1e-6);
  EXPECT_NEAR(face(h, 0).vertices[1].x.to_double(), 100, 1e-6);
}

struct BadObj {
  std::string text;
  int line;
  const char* phrase;
};

TEST(SceneObj, ErrorsNameTheLine) {
  using namespace std::string_literals;  // "..."s keeps the embedded NUL
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-3
  const BadObj cases[] = {
      {tri + "f 0 1 2\n", 4, "face vertex 1 index 0 is invalid (OBJ indices start at 1"},
      {tri + "f 1 2 4\n", 4, "face vertex 3 index 4 is out of range (3 defined so far)"},
      {tri + "f -4 1 2\n", 4, "index -4 is out of range"},
      {"f 1 2 3\n" + tri, 1, "out of range (0 defined so far)"},
      {tri + "f 1 2 -9223372036854775808\n", 4, "out of range"},
      {tri + "f 1 2 99999999999999999999\n", 4, "is not an integer"},
      {tri + "f 1 2 x\n", 4, "face vertex 3 index 'x' is not an integer"},
      {tri + "f 1 2\n", 4, "'f' needs at least 3 vertices, got 2"},
      {tri + "f 1/ 2 3\n", 4, "'1/' is not of the form i, i/t, i//n or i/t/n"},
      {tri + "f /1 2 3\n", 4, "is not of the form"},
      {tri + "f 1/1/ 2 3\n", 4, "is not of the form"},
      {tri + "f 1/1/1/1 2 3\n", 4, "more than three"},
      {tri + "f 1/1 2 3\n", 4, "face vertex 1 texture index 1 is out of range (0 defined so far)"},
      {tri + "vn 0 0 1\nf 1//2 2 3\n", 5, "normal index 2 is out of range (1 defined so far)"},
      {"v 1 2 x\n", 1, "z 'x' is not a finite number"},
      {"v 1 nan 0\n", 1, "y 'nan' is not a finite number"},
      {"v inf 0 0\n", 1, "x 'inf' is not a finite number"},
      {"v 1e999 0 0\n", 1, "is not a finite number"},
      {"v 1e-999 0 0\n", 1, "is not a finite number"},
      {"v +-1 0 0\n", 1, "x '+-1' is not a finite number"},
      {"v 1 2 3 +\n", 1, "w '+' is not a finite number"},
      {"v 0x10 0 0\n", 1, "is not a finite number"},
      {"v 1.5.2 0 0\n", 1, "is not a finite number"},
      {"v 1 2\n", 1, "'v' takes x y z, x y z w or x y z r g b, got 2"},
      {"v 1 2 3 4 5\n", 1, "got 5"},
      {"v 1 2 3 w\n", 1, "w 'w' is not a finite number"},
      {"v 1 2 3 0.5 1.5 0\n", 1, "green '1.5' is outside [0, 1]"},
      {"vt\n", 1, "'vt' takes 1 to 3 numbers, got 0"},
      {"vn 1 2\n", 1, "'vn' takes 3 numbers, got 2"},
      {"vn 1 2 z\n", 1, "'vn' component 'z' is not a finite number"},
      {"\n\nusemtl red\n", 3, "unknown material 'red'"},
      {"mtllib cube.mtl\nusemtl green\n", 2, "unknown material 'green'"},
      {"usemtl\n", 1, "'usemtl' needs a material name"},
      {"# x\nmtllib missing.mtl\n", 2, "cannot open material library 'missing.mtl'"},
      {"mtllib\n", 1, "'mtllib' needs a file name"},
      {"mtllib .\n", 1, "cannot open material library '.'"},
      {"curv 0 1 1 2\n", 1, "unknown OBJ statement 'curv'"},
      {tri + "f 1 2 3\nv 0 0\0 0\n"s, 5, "NUL byte"},
      {"v 1 2 3\n# no faces\n", 2, "no faces"},
      {"", 1, "no faces"},
      {"# c\n\n\n", 3, "no faces"},
  };
  for (const BadObj& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_TRUE(SceneFails([&] { parse(c.text); }, "m.obj:" + std::to_string(c.line) + ":", c.phrase));
  }
}

TEST(SceneObj, MtlErrorsNameTheMtlFile) {
  EXPECT_TRUE(SceneFails([] { parse("mtllib bad_kd.mtl\n"); }, kData + "/bad_kd.mtl:4:",
                         "Kd '1.5' is outside [0, 1]"));
  // MTL syntax errors, through a scratch MTL beside a scratch directory's OBJ.
  const auto dir = std::filesystem::temp_directory_path() / "rastsim_scene_obj_mtl";
  std::filesystem::create_directories(dir);
  const BadObj mtls[] = {
      {"Kd 1 1 1\n", 1, "'Kd' before any 'newmtl'"},
      {"newmtl\n", 1, "'newmtl' needs a material name"},
      {"newmtl a\nKd 1 1\n", 2, "'Kd' takes r g b"},
      {"newmtl a\nKd spectral x.rfl\n", 2, "'Kd spectral' is not supported (only 'Kd r g b')"},
      {"newmtl a\nKd xyz 1 1 1\n", 2, "'Kd xyz' is not supported"},
      {"newmtl a\nKd 1 one 1\n", 2, "Kd 'one' is not a finite number"},
      {"newmtl a\nKd 1 -0.5 1\n", 2, "Kd '-0.5' is outside [0, 1]"},
  };
  for (const BadObj& c : mtls) {
    SCOPED_TRACE(c.text);
    std::ofstream((dir / "m.mtl").string()) << c.text;
    EXPECT_TRUE(SceneFails([&] { parse_obj("mtllib m.mtl\n", "x.obj", flat(), dir.string()); },
                           (dir / "m.mtl").string() + ":" + std::to_string(c.line) + ":", c.phrase));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rastsim
