// SPDX-License-Identifier: Apache-2.0
// The OBJ and MTL targets' shared half: parse an OBJ text under two placements (the
// default config's and an extreme one within the config's ranges) and check the placed
// scene against the placement docs/trace-format.md describes.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "config/config.h"
#include "fuzz_common.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim::fuzz {

// Every corner lies inside the bounding sphere, which spans `fill` of the smaller
// viewport side about the viewport centre: |x - W/2|, |y - H/2| <= fill * min(W, H) / 2
// (with slack for rounding), depth in [0, 1], and each face a whole number of triangles.
inline void check_placed(const Scene& s, const ObjPlacement& p) {
  check(s.commands.size() >= 3, "an accepted OBJ has a clear, a clear depth and at least one face");
  const double r = p.fill * std::min(p.viewport_width, p.viewport_height) / 2.0 * (1 + 1e-9) + 1e-6;
  for (const Command& c : s.commands) {
    const auto* prim = std::get_if<CmdPrimitives>(&c.body);
    if (!prim) continue;
    const std::string at = "line " + std::to_string(c.loc.line) + ": ";
    if (p.camera == ObjCamera::Perspective) {  // clip space: finite binary32, w the eye distance's sign
      check(prim->vertices.empty() && !prim->clip_vertices.empty(), at + "a perspective command not in clip space");
      for (const ClipVertex& v : prim->clip_vertices)
        check(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w) &&
                  std::isfinite(v.s) && std::isfinite(v.t),
              at + "a clip-space value not finite");
      continue;
    }
    check(prim->topology == Topology::List && prim->vertices.size() >= 3 && prim->vertices.size() % 3 == 0,
          at + "a face is not a list of triangles");
    for (const SceneVertex& v : prim->vertices) {
      check(!v.x.saturated() && !v.y.saturated(), at + "placed coordinate saturated");
      const double dx = v.x.to_double() - p.viewport_width / 2.0, dy = v.y.to_double() - p.viewport_height / 2.0;
      check(std::abs(dx) <= r && std::abs(dy) <= r, at + "placed vertex outside the bounding sphere's square");
      check(v.z >= 0.0 && v.z <= 1.0, at + "placed depth outside [0, 1]");
    }
  }
}

// Parses `text` (named name, mtllib looked up in base_dir) under both placements.
inline void parse_and_check_obj(const std::string& text, const std::string& name, const std::string& base_dir) {
  ObjPlacement def = obj_placement_from_config(Config{});
  ObjPlacement extreme = def;  // the config's limits: fill 4, yaw -360, pitch 90, a 16384 x 1 viewport
  extreme.viewport_width = 16384;
  extreme.viewport_height = 1;
  extreme.fill = 4.0;
  extreme.yaw_deg = -360;
  extreme.pitch_deg = 90;
  ObjPlacement perspective = def;  // the perspective camera, its eye inside the mesh
  perspective.camera = ObjCamera::Perspective;
  perspective.distance = 0.5;
  for (const ObjPlacement& p : {def, extreme, perspective})
    expect_only<SceneError>("SceneError", [&] { check_placed(parse_obj(text, name, p, base_dir), p); });
}

}  // namespace rastsim::fuzz
