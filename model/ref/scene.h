// SPDX-License-Identifier: Apache-2.0
// Scene = the command stream the pipeline consumes (what command fetch reads).
//
// Two sources produce it: line-based traces (traces/*.trace, docs/trace-format.md) and
// Wavefront OBJ meshes placed by a camera/viewport transform (scene_obj.cpp). Both
// keep the file and line of every command so later stages can name them in errors.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "fixed_point.h"

namespace rastsim {

// A parse or scene error; what() is "file:line: what is wrong".
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SourceLoc {
  std::string file;  // shared by all commands of a scene; short, so copies are cheap
  int line = 0;
  std::string str() const { return file + ":" + std::to_string(line); }
};

// One vertex as the scene gives it: position in pixels (y down, exact Q64), depth in
// [0, 1] and an RGB8 colour.
struct SceneVertex {
  Q64 x, y;
  double z = 0.0;
  uint8_t r = 255, g = 255, b = 255;
};

enum class Topology { List, Strip, Fan };

struct CmdViewport { int width = 0, height = 0; };        // viewport W H
struct CmdClear { uint8_t r = 0, g = 0, b = 0; };         // clear colour (A = 255)
struct CmdClearDepth { double z = 1.0; };                 // clear depth in [0, 1]
struct CmdScissor { bool enabled = false; int x = 0, y = 0, width = 0, height = 0; };
struct CmdPrimitives {                                    // tri / strip / fan
  Topology topology = Topology::List;
  std::vector<SceneVertex> vertices;
};

using CommandBody = std::variant<CmdViewport, CmdClear, CmdClearDepth, CmdScissor, CmdPrimitives>;

struct Command {
  CommandBody body;
  SourceLoc loc;
};

struct Scene {
  std::string source;                 // file name
  std::vector<Command> commands;
};

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
