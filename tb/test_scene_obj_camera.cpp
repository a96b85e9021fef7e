// SPDX-License-Identifier: Apache-2.0
// The OBJ perspective camera (scene.camera = "perspective"; docs/trace-format.md,
// "Perspective camera"): clip-space positions worked by hand on meshes whose view-space
// positions are exact, the mesh centre at NDC (0, 0), winding kept, a camera inside the
// mesh, `vt` texture coordinates, `l` and `p` as clip-space lines and points, concave
// faces triangulated in their plane, and the keys' checks.
#include <gtest/gtest.h>

#include <bit>
#include <string>

#include "scene_test.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;

const std::string kData = RASTSIM_TEST_DATA;

// Head-on (no yaw or pitch), fov 90 deg (f = 1), near 1, far 3, the eye 2 radii from the
// centre: w_c = 2 - z, z_c = 1.5 w_c - 1.5.
ObjPlacement camera(int w = 100, int h = 100) {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.camera = ObjCamera::Perspective;
  p.viewport_width = w;
  p.viewport_height = h;
  p.yaw_deg = 0;
  p.pitch_deg = 0;
  p.fov_deg = 90;
  p.near = 1;
  p.far = 3;
  p.distance = 2;
  return p;
}

Scene parse(const std::string& text, const ObjPlacement& p) { return parse_obj(text, "m.obj", p, kData); }

const CmdPrimitives& prims(const Scene& s, size_t i) { return std::get<CmdPrimitives>(s.commands.at(i).body); }

// scene_test::kOcta (view space: the unit octahedron) and its centre as a seventh vertex
// with a face through it.
const std::string kOcta = std::string(scene_test::kOcta) + "v 0 0 0\nf 1 3 7\n";

void expect_clip(const ClipVertex& v, float x, float y, float z, float w) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
  EXPECT_EQ(v.w, w);
}

// x_c = (f / aspect) x, y_c = -f y, w_c = 2 - z, z_c = 1.5 w_c - 1.5, by hand: (1, 0, 0)
// -> (0.5, 0, 1.5, 2) on a 2:1 viewport; (0, 1, 0) -> (0, -1, 1.5, 2); (0, 0, 1), on the
// near plane, -> (0, 0, 0, 1); (0, 0, -1), on the far plane, -> (0, 0, 3, 3).
TEST(SceneObjCamera, HandComputedClipCoordinates) {
  const Scene s = parse(kOcta, camera(200, 100));
  ASSERT_EQ(s.commands.size(), 5u);
  const CmdPrimitives& front = prims(s, 2);
  EXPECT_TRUE(front.vertices.empty());
  EXPECT_EQ(front.topology, Topology::List);
  EXPECT_EQ(front.clip, ClipState{});  // the whole viewport, depth 0..1
  ASSERT_EQ(front.clip_vertices.size(), 3u);
  expect_clip(front.clip_vertices[0], 0.5f, 0, 1.5f, 2);
  expect_clip(front.clip_vertices[1], 0, -1, 1.5f, 2);
  expect_clip(front.clip_vertices[2], 0, 0, 0, 1);
  const CmdPrimitives& back = prims(s, 3);
  expect_clip(back.clip_vertices[0], -0.5f, 0, 1.5f, 2);
  expect_clip(back.clip_vertices[1], 0, 0, 3, 3);
  expect_clip(back.clip_vertices[2], 0, 1, 1.5f, 2);
  EXPECT_EQ(s.commands[2].loc.line, 7);
}

// fov 60: f = 1/tan(30 deg) = sqrt(3) = 1.7320508075688772..., whose nearest binary32 is
// 0x3FDDB3D7 (1.73205077648162841796875): one rounding from the double.
TEST(SceneObjCamera, OneRoundingToBinary32) {
  ObjPlacement p = camera();
  p.fov_deg = 60;
  const ClipVertex v = prims(parse(kOcta, p), 2).clip_vertices[0];
  EXPECT_EQ(std::bit_cast<uint32_t>(v.x), 0x3FDDB3D7u);
  EXPECT_EQ(std::bit_cast<uint32_t>(-prims(parse(kOcta, p), 2).clip_vertices[1].y), 0x3FDDB3D7u);
}

// The mesh centre is on the view axis whatever the view: NDC (0, 0), w = distance.
TEST(SceneObjCamera, MeshCentreLandsAtNdcOrigin) {
  for (const double yaw : {0.0, 30.0, -135.0})
    for (const double pitch : {0.0, 20.0, -90.0}) {
      SCOPED_TRACE(std::to_string(yaw) + " " + std::to_string(pitch));
      ObjPlacement p = camera(640, 480);
      p.yaw_deg = yaw;
      p.pitch_deg = pitch;
      p.fov_deg = 45;
      p.distance = 2.5;
      const ClipVertex c = prims(parse(kOcta, p), 4).clip_vertices[2];
      EXPECT_EQ(c.x, 0.0f);
      EXPECT_EQ(c.y, 0.0f);
      EXPECT_EQ(c.w, 2.5f);
    }
}

// Doubled signed area in NDC with y down (screen orientation): negative is
// counter-clockwise on screen, front-facing with raster.front_ccw (as the ortho camera).
double ndc_area2(const std::vector<ClipVertex>& v) {
  auto x = [&](int i) { return double(v[i].x) / v[i].w; };
  auto y = [&](int i) { return double(v[i].y) / v[i].w; };
  return (x(1) - x(0)) * (y(2) - y(0)) - (y(1) - y(0)) * (x(2) - x(0));
}

TEST(SceneObjCamera, WindingIsKept) {
  const Scene s = parse(kOcta, camera());
  EXPECT_LT(ndc_area2(prims(s, 2).clip_vertices), 0);  // the front face: counter-clockwise on screen
  EXPECT_GT(ndc_area2(prims(s, 3).clip_vertices), 0);  // the back face: clockwise
}

// distance 0.5: the eye is inside the mesh, between its centre and the front vertex
// (0, 0, 1), which is behind it (w = -0.5); the back one is at w = 1.5. Nothing is
// dropped: the front end clips.
TEST(SceneObjCamera, CameraInsideTheMesh) {
  ObjPlacement p = camera();
  p.distance = 0.5;
  p.near = 0.1;
  const Scene s = parse(kOcta, p);
  EXPECT_EQ(prims(s, 2).clip_vertices[2].w, -0.5f);
  EXPECT_EQ(prims(s, 3).clip_vertices[1].w, 1.5f);
  EXPECT_EQ(prims(s, 4).clip_vertices[2].w, 0.5f);  // the centre
  EXPECT_LT(prims(s, 2).clip_vertices[2].z, 0.0f);  // in front of the near plane: z < 0
}

// vt u v -> s = u, t = 1 - v; `vt u` has v = 0; a corner without one (0, 0). Both
// cameras carry them.
TEST(SceneObjCamera, TextureCoordinatesTravelWithTheVertices) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "vt 0.25 0.75\nvt 0.5\nvt -1 0.1 7\nvn 0 0 1\n"
      "f 1/1 2/2 3/3\n"
      "f 1 2/1 3//1\n";
  for (const bool perspective : {false, true}) {
    SCOPED_TRACE(perspective);
    ObjPlacement p = camera();
    if (!perspective) p.camera = ObjCamera::Ortho;
    const Scene s = parse(obj, p);
    auto st = [&](size_t face, size_t k) -> std::pair<float, float> {
      const CmdPrimitives& c = prims(s, 2 + face);
      if (perspective) return {c.clip_vertices.at(k).s, c.clip_vertices.at(k).t};
      return {c.vertices.at(k).s, c.vertices.at(k).t};
    };
    EXPECT_EQ(st(0, 0), std::pair(0.25f, 0.25f));
    EXPECT_EQ(st(0, 1), std::pair(0.5f, 1.0f));
    EXPECT_EQ(st(0, 2), std::pair(-1.0f, 0.9f));
    EXPECT_EQ(st(1, 0), std::pair(0.0f, 0.0f));
    EXPECT_EQ(st(1, 1), std::pair(0.25f, 0.25f));
    EXPECT_EQ(st(1, 2), std::pair(0.0f, 0.0f));
    EXPECT_EQ(s.obj_ignored, (StatementCounts{{"vn", 1}}));  // vt is used now
  }
}

// `l` is a LineStrip and `p` Points, each its own command between the faces' Lists,
// unlit (the vertex colour as written), named by its line.
TEST(SceneObjCamera, LinesAndPointsAreClipSpaceCommands) {
  ObjPlacement p = camera();
  p.faces_per_command = 8;
  const Scene s = parse(
      "v 5 0 0 1 0 0\nv -5 0 0\nv 0 5 0\nv 0 -5 0\nv 0 0 5\nv 0 0 -5\n"
      "f 1 3 5\nl 1 2 3 1\nf 2 6 4\nf 1 4 6\np 5 -1\n",
      p);
  ASSERT_EQ(s.commands.size(), 6u);
  EXPECT_EQ(prims(s, 2).clip_vertices.size(), 3u);
  const CmdPrimitives& l = prims(s, 3);
  EXPECT_EQ(l.topology, Topology::LineStrip);
  EXPECT_EQ(s.commands[3].loc.line, 8);
  ASSERT_EQ(l.clip_vertices.size(), 4u);  // a closed polyline repeats its first vertex
  expect_clip(l.clip_vertices[0], 1, 0, 1.5f, 2);
  EXPECT_EQ(l.clip_vertices[0].r, 255);  // the vertex colour (1, 0, 0), unshaded
  EXPECT_EQ(l.clip_vertices[0].g, 0);
  EXPECT_EQ(l.clip_vertices[1].g, 255);  // white
  EXPECT_EQ(prims(s, 4).clip_vertices.size(), 6u);  // the two faces after it share a List
  const CmdPrimitives& pt = prims(s, 5);
  EXPECT_EQ(pt.topology, Topology::Points);
  ASSERT_EQ(pt.clip_vertices.size(), 2u);
  expect_clip(pt.clip_vertices[0], 0, 0, 0, 1);
  expect_clip(pt.clip_vertices[1], 0, 0, 3, 3);
}

TEST(SceneObjCamera, LinesAndPointsErrors) {
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_TRUE(SceneFails([&] { parse(verts + "l 1\n", camera()); }, "m.obj:5:", "'l' needs at least 2 vertices, got 1"));
  EXPECT_TRUE(SceneFails([&] { parse(verts + "p\n", camera()); }, "m.obj:5:", "'p' needs at least 1 vertex, got 0"));
  EXPECT_TRUE(SceneFails([&] { parse(verts + "p 4\n", camera()); }, "m.obj:5:", "vertex 1 index 4 is out of range"));
  ObjPlacement ortho = camera();
  ortho.camera = ObjCamera::Ortho;
  EXPECT_TRUE(SceneFails([&] { parse(verts + "l 1 2\n", ortho); }, "m.obj:5:",
                         "'l' (polyline) statements are drawn by the perspective camera only"));
  ortho.lines_points = ObjLinesPoints::Skip;
  EXPECT_EQ(parse(verts + "l 1 2\np 1\n", ortho).obj_ignored, (StatementCounts{{"l", 1}, {"p", 1}}));
  // A file of points alone draws with the perspective camera, not with the ortho one.
  EXPECT_EQ(parse("v 0 0 0\np 1\n", camera()).commands.size(), 3u);
  EXPECT_TRUE(SceneFails([&] { parse("v 0 0 0\np 1\n", ortho); }, "m.obj:2:", "no faces"));
  EXPECT_TRUE(SceneFails([&] { parse("v 0 0 0\n", camera()); }, "m.obj:1:", "no faces, lines or points"));
}

// The dart (-1,-1) (0,0) (1,-1) (0,2) in the z = 0 plane (docs/trace-format.md, "Polygon
// faces"), concave at corner 2: ear-clipped in its own plane to (4, 1, 2), (2, 3, 4),
// whatever the view, where the fan's (1, 2, 3) would lie in the notch.
TEST(SceneObjCamera, ConcaveFacesAreTriangulatedInTheirPlane) {
  const std::string dart = "v -1 -1 0\nv 0 0 0\nv 1 -1 0\nv 0 2 0\nf 1 2 3 4\n";
  for (const double yaw : {0.0, 80.0}) {
    ObjPlacement p = camera();
    p.yaw_deg = yaw;
    const Scene s = parse(dart, p);
    const CmdPrimitives& c = prims(s, 2);
    ASSERT_EQ(c.clip_vertices.size(), 6u);
    // The same corners as points (same camera, same bounding sphere): their positions
    // tell the triangles' corners apart (x, then y for corners 2 and 4).
    const Scene flat = parse(dart + "p 1 2 3 4\n", p);
    const std::vector<ClipVertex>& corner = prims(flat, 3).clip_vertices;
    const int want[] = {3, 0, 1, 1, 2, 3};
    for (size_t i = 0; i < 6; ++i) {
      EXPECT_EQ(c.clip_vertices[i].x, corner[size_t(want[i])].x) << i;
      EXPECT_EQ(c.clip_vertices[i].y, corner[size_t(want[i])].y) << i;
    }
  }
  EXPECT_TRUE(SceneFails([&] { parse("v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n", camera()); }, "m.obj:5:",
                         "the face crosses itself"));
}

TEST(SceneObjCamera, PlacementAndKeyChecks) {
  ObjPlacement p = camera();
  p.far = 1;  // not beyond near
  EXPECT_TRUE(SceneFails([&] { parse(kOcta, p); }, "m.obj:", "0 < near < far"));
  p = camera();
  p.fov_deg = 180;
  EXPECT_TRUE(SceneFails([&] { parse(kOcta, p); }, "m.obj:", "field of view in (0, 180)"));
  Config c;
  EXPECT_EQ(obj_placement_from_config(c).camera, ObjCamera::Ortho);  // the default: today's placement
  c.apply_override("scene.camera=perspective");
  c.apply_override("scene.near=2");
  c.apply_override("scene.far=2");
  EXPECT_THROW(obj_placement_from_config(c), ConfigError);
  c.apply_override("scene.far=2.5");
  const ObjPlacement q = obj_placement_from_config(c);
  EXPECT_EQ(q.camera, ObjCamera::Perspective);
  EXPECT_EQ(q.fov_deg, 60.0);
  EXPECT_EQ(q.distance, 2.5);
  EXPECT_THROW(c.apply_override("scene.camera=fisheye"), ConfigError);
  EXPECT_THROW(c.apply_override("scene.fov_deg=180"), ConfigError);
}

}  // namespace
}  // namespace rastsim
