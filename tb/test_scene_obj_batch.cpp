// SPDX-License-Identifier: Apache-2.0
// scene.obj_faces_per_command: an OBJ mesh sent as List commands of N faces holds the
// same triangles in the same order as one command a face; the commands are ceil(F / N),
// each named by its first face's line (worked by hand on a five-face mesh with a quad).
#include <gtest/gtest.h>

#include "config/config.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

// Faces on lines 6..10; the quad on line 8 fans into two triangles: 6 triangles in all.
const char* kMesh =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 2 3\n"
    "f 1 3 4\n"
    "f 1 2 3 4\n"
    "f 1 2 5\n"
    "f 2 3 5\n";

Scene parse(int faces_per_command) {
  ObjPlacement p = obj_placement_from_config(Config{});
  p.faces_per_command = faces_per_command;
  return parse_obj(kMesh, "m.obj", p, ".");
}

TEST(SceneObjBatch, SameTrianglesFewerCommands) {
  const Scene one = parse(1);
  ASSERT_EQ(one.commands.size(), 2u + 5u);  // clear, clear depth, one command a face
  std::vector<SceneVertex> want;
  for (size_t c = 2; c < one.commands.size(); ++c) {
    const auto& v = std::get<CmdPrimitives>(one.commands[c].body).vertices;
    want.insert(want.end(), v.begin(), v.end());
  }
  ASSERT_EQ(want.size(), 18u);  // 6 triangles
  struct Case {
    int n;
    std::vector<int> lines;       // the first face's line of each command
    std::vector<size_t> triangles;  // triangles in each command
  };
  for (const Case& c : {Case{2, {6, 8, 10}, {2, 3, 1}}, Case{3, {6, 9}, {4, 2}}, Case{5, {6}, {6}},
                        Case{1000, {6}, {6}}}) {
    SCOPED_TRACE("faces_per_command " + std::to_string(c.n));
    const Scene s = parse(c.n);
    ASSERT_EQ(s.commands.size(), 2 + c.lines.size());
    std::vector<SceneVertex> got;
    for (size_t k = 0; k < c.lines.size(); ++k) {
      const auto& cmd = s.commands[2 + k];
      EXPECT_EQ(cmd.loc.line, c.lines[k]);
      const auto& p = std::get<CmdPrimitives>(cmd.body);
      EXPECT_EQ(p.topology, Topology::List);
      EXPECT_EQ(p.vertices.size(), 3 * c.triangles[k]);
      got.insert(got.end(), p.vertices.begin(), p.vertices.end());
    }
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].x.q, want[i].x.q) << i;
      EXPECT_EQ(got[i].y.q, want[i].y.q) << i;
      EXPECT_EQ(got[i].z, want[i].z) << i;
      EXPECT_EQ(got[i].r, want[i].r) << i;
    }
  }
}

TEST(SceneObjBatch, ConfigKey) {
  EXPECT_EQ(Config{}.get_int("scene.obj_faces_per_command"), 1);
  Config c;
  c.apply_override("scene.obj_faces_per_command=4096");
  EXPECT_EQ(obj_placement_from_config(c).faces_per_command, 4096);
  EXPECT_THROW(c.apply_override("scene.obj_faces_per_command=0"), ConfigError);
  ObjPlacement p = obj_placement_from_config(Config{});
  p.faces_per_command = 0;
  EXPECT_THROW(parse_obj(kMesh, "m.obj", p, "."), SceneError);
}

}  // namespace
}  // namespace rastsim
