// SPDX-License-Identifier: Apache-2.0
// The scene readers: trace files (scene_trace.cpp) and Wavefront OBJ meshes with their
// MTL files (scene_obj.cpp), into the command stream of ref/scene.h.
#pragma once

#include <string>

#include "ref/scene.h"

namespace rastsim {

// Where an OBJ mesh lands on screen: a camera looking at the mesh's bounding sphere.
struct ObjPlacement {
  int viewport_width = 128, viewport_height = 128;
  double yaw_deg = 30.0, pitch_deg = 20.0;  // rotation of the model about y, then x
  double fill = 0.9;                         // fraction of the viewport the sphere spans
  uint8_t clear_r = 0, clear_g = 0, clear_b = 0;
};

// Parse a trace file. Throws SceneError("file:line: ...") on any malformed input.
Scene load_trace(const std::string& path);
Scene parse_trace(const std::string& text, const std::string& name);

// Parse a Wavefront OBJ (with its mtllib files, looked up beside it) and place it.
Scene load_obj(const std::string& path, const ObjPlacement& placement);
Scene parse_obj(const std::string& text, const std::string& name, const ObjPlacement& placement,
                const std::string& base_dir);

// By extension: .obj -> load_obj, anything else -> load_trace.
Scene load_scene(const std::string& path, const ObjPlacement& placement);

}  // namespace rastsim
