// SPDX-License-Identifier: Apache-2.0
// Keys of OBJ mesh placement (model/scene/scene_obj.cpp): where a mesh lands on screen.
// Not architecture: they choose the workload's view, so a real mesh (the Stanford bunny,
// Y-up; glmark2's horse and cat, Z-up) can be shown upright from any side.
#include "config/config_schema.h"

#include <algorithm>
#include <stdexcept>

namespace rastsim {

namespace {

// scene.obj_depth_func: the depth test an OBJ mesh draws with. A mesh is a closed
// surface seen from outside, so without a depth test its back faces overwrite the front
// ones wherever they are drawn later; "less" (clear depth 1, the reader's depth 0 near ..
// 1 far) hides them whatever the config's raster.depth_func, which traces keep. "config"
// takes raster.depth_func as it is. The names are raster.depth_func's, read from the
// schema being built (it is declared before the scene keys), so the two lists are one.
ParamDef obj_depth_func_param(const std::vector<ParamDef>& s) {
  const auto raster = std::find_if(s.begin(), s.end(), [](const ParamDef& d) { return d.key == "raster.depth_func"; });
  if (raster == s.end()) throw std::logic_error("scene.obj_depth_func: raster.depth_func must be declared first");
  std::vector<std::string> names{"config"};
  names.insert(names.end(), raster->choices.begin(), raster->choices.end());
  return {"scene.obj_depth_func", ParamType::Enum, std::string("less"), "", 1, 0, names,
          "OBJ placement: the depth test a mesh draws with, in place of raster.depth_func (config: "
          "raster.depth_func's own; traces always take raster.depth_func)"};
}

// The OBJ camera (docs/trace-format.md, "Perspective camera"). Lengths are in units of
// the mesh's bounding radius, so one setting frames any mesh whatever units it is written
// in; scene.far > scene.near is checked by obj_placement_from_config.
void add_camera_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"scene.camera", T::Enum, std::string("ortho"), "", 1, 0, {"ortho", "perspective"},
               "OBJ placement: ortho (screen-space triangles, the bounding sphere spanning scene.obj_fill) or "
               "perspective (clip-space vertices in binary32 through the geometry front end, docs/clip-space.md)"});
  s.push_back({"scene.fov_deg", T::Float, 60.0, "deg", 1.0, 179.0, {},
               "OBJ perspective camera: vertical field of view"});
  s.push_back({"scene.near", T::Float, 0.1, "radii", 1e-6, 1e6, {},
               "OBJ perspective camera: near plane distance from the eye, in bounding radii of the mesh "
               "(depth z/w = 0 there; nearer geometry is clipped)"});
  s.push_back({"scene.far", T::Float, 100.0, "radii", 1e-6, 1e6, {},
               "OBJ perspective camera: far plane distance from the eye, in bounding radii (depth 1; must exceed "
               "scene.near)"});
  s.push_back({"scene.distance", T::Float, 2.5, "radii", 0.0, 1e6, {},
               "OBJ perspective camera: eye distance from the mesh centre along the view axis, in bounding radii "
               "(below 1 the eye may be inside the mesh)"});
}

}  // namespace

void add_scene_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  // The up axis is applied first (an exact quarter or half turn, never a mirror, so the
  // winding of every face and hence culling is kept); yaw and pitch then turn the upright
  // mesh like a turntable camera: yaw about the vertical, pitch toward the viewer. With
  // an up axis, (yaw, pitch) is a full view direction, so there is no separate view key:
  // front (+z after the up turn) 0/0, the -x side 90/0, the +x side -90/0, back 180/0,
  // top 0/90, bottom 0/-90 (docs/exploration.md, "Real workloads").
  s.push_back({"scene.obj_up", T::Enum, std::string("y"), "", 1, 0, {"y", "z", "-y", "-z", "x", "-x"},
               "OBJ placement: the mesh's up axis, turned to screen up before yaw and pitch "
               "(y: OBJ's convention; z: 3ds Max, Blender, CAD)"});
  s.push_back({"scene.obj_yaw_deg", T::Float, 30.0, "deg", -360, 360, {},
               "OBJ placement: rotation of the mesh about its vertical axis (90: its -x side faces the viewer)"});
  s.push_back({"scene.obj_pitch_deg", T::Float, 20.0, "deg", -90, 90, {},
               "OBJ placement: tilt of the mesh toward the viewer, after the yaw (90: seen from the top)"});
  s.push_back({"scene.obj_fill", T::Float, 0.9, "", 0.01, 4.0, {},
               "OBJ placement: fraction of the smaller viewport side the mesh's bounding sphere spans"});
  // The workload's form, not its geometry: command fetch pays a header per command
  // (fetch.cycles_per_command), so one command a face costs a real mesh a cycle a
  // triangle that a driver batching its draw calls would not (docs/exploration.md).
  s.push_back({"scene.obj_faces_per_command", T::Int, int64_t{1}, "faces", 1, 1 << 30, {},
               "OBJ reading: faces sent in one List command (1: each face its own command; "
               "larger: batched as in one draw call), same triangles in the same order"});
  s.push_back({"scene.obj_order", T::Enum, std::string("file"), "", 1, 0, {"file", "front_to_back", "back_to_front"},
               "OBJ reading: the order faces are drawn in: the file's, or sorted by each face's nearest corner "
               "(nearest or farthest first, ties in file order; l and p statements after the faces): the "
               "depth-culling studies (docs/depth-culling.md)"});
  s.push_back(obj_depth_func_param(s));
  // 3D points and lines need depth through the clip-space front end: with the
  // perspective camera they become clip-space Points / Lines commands; the orthographic
  // placement makes screen-space triangles only, so there the reader refuses or skips them.
  s.push_back({"scene.obj_lines_points", T::Enum, std::string("error"), "", 1, 0, {"error", "skip"},
               "OBJ reading with scene.camera = ortho: 'l' (polyline) and 'p' (point) statements, which only the "
               "perspective camera draws (error: stop at the first with its file:line; skip: leave them out, "
               "counted in obj_ignored); with scene.camera = perspective they are drawn"});
  // MTL has no texture filter or mipmap statement: a textured face draws with these (a
  // trace sets them with texfilter and mipmap), so one mesh can be drawn in each filter
  // mode (the filter-mode study, scripts/texture_study).
  s.push_back({"scene.obj_texfilter", T::Enum, std::string("bilinear"), "", 1, 0, {"nearest", "bilinear", "trilinear"},
               "OBJ reading: the texture filter a textured (map_Kd) face draws with, as a trace's texfilter"});
  s.push_back({"scene.obj_mipmap", T::Bool, false, "", 1, 0, {},
               "OBJ reading: textured faces sample the mip chain (a trace's mipmap on), else level 0 only"});
  add_camera_params(s);
}

}  // namespace rastsim
