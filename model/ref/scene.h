// SPDX-License-Identifier: Apache-2.0
// Scene = the command stream the pipeline consumes (what command fetch reads).
//
// Two readers produce it (model/scene): line-based traces (traces/*.trace,
// docs/trace-format.md) and Wavefront OBJ meshes placed by a camera/viewport transform.
// Both keep the file and line of every command so later stages can name them in errors.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "ref/fixed_point.h"

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

}  // namespace rastsim
