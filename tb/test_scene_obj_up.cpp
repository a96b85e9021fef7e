// SPDX-License-Identifier: Apache-2.0
// OBJ placement's up axis (scene.obj_up): a mesh authored with another up axis lands
// exactly where the same mesh authored Y-up lands; the vertex on each up axis goes to the
// top of the screen (worked by hand); the turn is never a mirror (front faces stay
// counter-clockwise on screen); the key's default and its errors from a config file.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/config.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

// Head-on (yaw 0, pitch 0), 100x100, the sphere spans the viewport: one unit of a
// radius-5 mesh is 10 px, the centre is (50, 50), y down on screen.
ObjPlacement head_on(ObjUp up) {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.viewport_width = 100;
  p.viewport_height = 100;
  p.yaw_deg = 0;
  p.pitch_deg = 0;
  p.fill = 1.0;
  p.up = up;
  return p;
}

Scene parse(const std::string& text, const ObjPlacement& p) { return parse_obj(text, "m.obj", p, "."); }

const CmdPrimitives& face(const Scene& s, size_t i) { return std::get<CmdPrimitives>(s.commands.at(2 + i).body); }

using P3 = std::array<double, 3>;

// A box [0,4] x [0,2] x [0,1] (every side a different length, so any wrong turn moves
// some corner) with one triangle per side, counter-clockwise seen from outside, written
// Y-up. `corner(x, y, z)` maps the Y-up corner to the coordinates of the file written.
template <class Map>
std::string box(Map corner) {
  std::string s;
  const double xs[2] = {0, 4}, ys[2] = {0, 2}, zs[2] = {0, 1};
  for (int i = 0; i < 8; ++i) {
    const auto p = corner(xs[i & 1], ys[(i >> 1) & 1], zs[(i >> 2) & 1]);
    s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  }
  // Corners 1..8: index - 1 has bit 0 x, bit 1 y, bit 2 z. Front (+z) 5 6 8, back (-z)
  // 2 1 3, right (+x) 6 2 4, left (-x) 3 1 5, top (+y) 4 3 7, bottom (-y) 5 1 2: each a
  // right triangle whose first and last corners are opposite corners of its side.
  return s + "f 5 6 8\nf 2 1 3\nf 6 2 4\nf 3 1 5\nf 4 3 7\nf 5 1 2\n";
}

TEST(SceneObjUp, OtherUpAxesLandWhereYUpLands) {
  // The same box written with each up axis: the file's coordinates of a Y-up corner
  // (x, y, z) for a mesh whose up is z is (x, -z, y) (Z-up's front is its -y side), and so
  // on: each the inverse of a quarter or half turn, worked by hand.
  const std::string y_up = box([](double x, double y, double z) { return P3{x, y, z}; });
  struct Case {
    ObjUp up;
    std::string text;
    const char* name;
  };
  const Case cases[] = {
      {ObjUp::PosZ, box([](double x, double y, double z) { return P3{x, -z, y}; }), "z"},
      {ObjUp::NegZ, box([](double x, double y, double z) { return P3{x, z, -y}; }), "-z"},
      {ObjUp::NegY, box([](double x, double y, double z) { return P3{x, -y, -z}; }), "-y"},
      {ObjUp::PosX, box([](double x, double y, double z) { return P3{y, -x, z}; }), "x"},
      {ObjUp::NegX, box([](double x, double y, double z) { return P3{-y, x, z}; }), "-x"},
  };
  // The default view (yaw 30, pitch 20) so that no turn hides behind a symmetry.
  ObjPlacement yp = obj_placement_from_config(Config{});
  const Scene want = parse(y_up, yp);
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string("obj_up = ") + c.name);
    ObjPlacement p = yp;
    p.up = c.up;
    const Scene got = parse(c.text, p);
    ASSERT_EQ(got.commands.size(), want.commands.size());
    for (size_t f = 0; f < 6; ++f) {
      const auto& g = face(got, f).vertices;
      const auto& w = face(want, f).vertices;
      ASSERT_EQ(g.size(), w.size());
      for (size_t k = 0; k < g.size(); ++k) {
        EXPECT_EQ(g[k].x.q, w[k].x.q) << "face " << f << " corner " << k;
        EXPECT_EQ(g[k].y.q, w[k].y.q) << "face " << f << " corner " << k;
        EXPECT_EQ(g[k].z, w[k].z) << "face " << f << " corner " << k;
        EXPECT_EQ(g[k].r, w[k].r) << "face " << f << " corner " << k;  // same shading
      }
    }
  }
}

TEST(SceneObjUp, TheUpVertexGoesToTheTopOfTheScreen) {
  // An octahedron of radius 5: vertices 1..6 at +x, -x, +y, -y, +z, -z. Head on, the
  // vertex on the up axis lands at (50, 0), the one opposite at (50, 100); for Z-up the
  // -y vertex (its front) is nearest (depth 0) at the centre, for Y-up the +z one.
  const char* octa = "v 5 0 0\nv -5 0 0\nv 0 5 0\nv 0 -5 0\nv 0 0 5\nv 0 0 -5\nf 1 3 5\nf 2 4 6\n";
  struct Case {
    ObjUp up;
    int top, bottom;  // 0-based vertex index on the up axis and opposite it
  };
  // Face 0 holds vertices 0 (+x), 2 (+y), 4 (+z); face 1 holds 1 (-x), 3 (-y), 5 (-z).
  auto where = [](const Scene& s, int v) { return face(s, v % 2).vertices[v / 2]; };
  for (const Case& c : {Case{ObjUp::PosY, 2, 3}, Case{ObjUp::NegY, 3, 2}, Case{ObjUp::PosZ, 4, 5},
                        Case{ObjUp::NegZ, 5, 4}, Case{ObjUp::PosX, 0, 1}, Case{ObjUp::NegX, 1, 0}}) {
    SCOPED_TRACE("up vertex " + std::to_string(c.top));
    const Scene s = parse(octa, head_on(c.up));
    EXPECT_EQ(where(s, c.top).x.q, Q64::from_int(50).q);
    EXPECT_EQ(where(s, c.top).y.q, Q64::from_int(0).q);
    EXPECT_EQ(where(s, c.top).z, 0.5);
    EXPECT_EQ(where(s, c.bottom).y.q, Q64::from_int(100).q);
  }
  // Z-up: +x stays screen right, -y (the front) is nearest, +y farthest.
  const Scene z = parse(octa, head_on(ObjUp::PosZ));
  EXPECT_EQ(where(z, 0).x.q, Q64::from_int(100).q);
  EXPECT_EQ(where(z, 3).z, 0.0);
  EXPECT_EQ(where(z, 2).z, 1.0);
  // X-up: +90 deg about z, so +y goes to screen left.
  EXPECT_EQ(where(parse(octa, head_on(ObjUp::PosX)), 2).x.q, Q64::from_int(0).q);
}

TEST(SceneObjUp, NoAxisIsAMirror) {
  // A closed box, every face counter-clockwise seen from outside: whatever the up axis,
  // the faces counter-clockwise on screen (doubled y-down area < 0) are exactly those
  // nearer the viewer than the box's centre (depth 0.5). A mirror would swap the two.
  const std::string text = box([](double x, double y, double z) { return P3{x, y, z}; });
  for (ObjUp up : {ObjUp::PosY, ObjUp::NegY, ObjUp::PosZ, ObjUp::NegZ, ObjUp::PosX, ObjUp::NegX}) {
    SCOPED_TRACE("up " + std::to_string(static_cast<int>(up)));
    ObjPlacement p = obj_placement_from_config(Config{});  // yaw 30, pitch 20: no face edge-on
    p.up = up;
    const Scene s = parse(text, p);
    int front = 0;
    for (size_t f = 0; f < 6; ++f) {
      const auto& v = face(s, f).vertices;
      const double a = (v[1].x.to_double() - v[0].x.to_double()) * (v[2].y.to_double() - v[0].y.to_double()) -
                       (v[1].y.to_double() - v[0].y.to_double()) * (v[2].x.to_double() - v[0].x.to_double());
      // The side's centre (midpoint of the first and last corners, opposite corners of
      // the side) is nearer than the box's centre exactly when the side faces the viewer.
      const double depth = (v[0].z + v[2].z) / 2;
      EXPECT_EQ(a < 0, depth < 0.5) << "face " << f;
      front += a < 0;
    }
    EXPECT_EQ(front, 3);  // a box seen from a general direction shows three sides
  }
}

TEST(SceneObjUp, ConfigKeyDefaultAndErrors) {
  EXPECT_EQ(Config{}.get_string("scene.obj_up"), "y");
  EXPECT_EQ(obj_placement_from_config(Config{}).up, ObjUp::PosY);
  Config c;
  c.apply_override("scene.obj_up=-z");
  EXPECT_EQ(obj_placement_from_config(c).up, ObjUp::NegZ);
  for (const char* name : {"y", "z", "-y", "-z", "x", "-x"}) EXPECT_TRUE(parse_obj_up(name)) << name;
  EXPECT_FALSE(parse_obj_up("+z"));
  // A bad axis in a file names the file, the line and the allowed values.
  const std::string path = (std::filesystem::temp_directory_path() / "rastsim_obj_up_test.toml").string();
  std::ofstream(path) << "[scene]\n\nobj_up = \"up\"\n";
  try {
    Config f;
    f.load_file(path);
    ADD_FAILURE() << "obj_up = \"up\" was accepted";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path + ":3"), std::string::npos) << m;
    EXPECT_NE(m.find("scene.obj_up"), std::string::npos) << m;
    EXPECT_NE(m.find("y, z, -y, -z, x, -x"), std::string::npos) << m;
  }
  std::remove(path.c_str());
  EXPECT_THROW(c.apply_override("scene.obj_up=w"), ConfigError);
}

}  // namespace
}  // namespace rastsim
