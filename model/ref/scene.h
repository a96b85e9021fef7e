// SPDX-License-Identifier: Apache-2.0
// Scene = the command stream the pipeline consumes (what command fetch reads).
//
// Two readers produce it (model/scene): line-based traces (traces/*.trace,
// docs/trace-format.md) and Wavefront OBJ meshes placed by a camera/viewport transform.
// Both keep the file and line of every command so later stages can name them in errors.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "ref/fixed_point.h"
#include "ref/texture/texture.h"

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

// One vertex on screen, as setup snaps it: position in pixels (y down, exact Q64), depth
// in [0, 1], a colour, and what the geometry front end adds to a clip-space vertex
// (docs/clip-space.md): the binary32 1/w that weights perspective-correct interpolation
// (1: affine, every screen-space vertex) and the texture coordinate (repeats, binary32).
// The colour is unsigned 8.F a channel (F = interp.color_frac_bits): the integer part
// r, g, b and the fraction bits rgb_frac (units 2^-F, 0 for every input vertex; a vertex
// clipping made has its binary32 colour rounded once into them).
struct SceneVertex {
  Q64 x, y;
  double z = 0.0;
  uint8_t r = 255, g = 255, b = 255;
  std::array<uint16_t, 3> rgb_frac{};  // r, g, b fraction bits, < 2^interp.color_frac_bits
  float inv_w = 1.0f;
  float s = 0.0f, t = 0.0f;
};

// One vertex in clip space, as a vertex stage hands it over (docs/clip-space.md):
// position in IEEE binary32, each read from its decimal text with one round to nearest
// even; colour r, g, b in binary32 (0..255: an input vertex's RGB8 exactly, a vertex
// clipping made interpolated); texture coordinate (s, t) in repeats, binary32.
struct ClipVertex {
  float x = 0.0f, y = 0.0f, z = 0.0f, w = 1.0f;
  float r = 255.0f, g = 255.0f, b = 255.0f;
  float s = 0.0f, t = 0.0f;
};

// Triangle topologies (prim_assembly.h) and, for clip-space primitives only, the 3D
// point and line topologies the front end expands into screen-aligned quads.
enum class Topology { List, Strip, Fan, Points, Lines, LineStrip, LineLoop };

// The front-end state a clip-space primitive is drawn with (`viewport_xform`,
// `depth_range`, `point_size`, `point_sprite`), carried by the command as a 2D command
// carries its style.
struct ViewportXform {
  bool whole_viewport = true;  // the default: the current `viewport` W x H at (0, 0)
  int x = 0, y = 0, width = 0, height = 0;  // pixels, when !whole_viewport
  bool operator==(const ViewportXform&) const = default;
};
struct ClipState {
  ViewportXform xform;
  float depth_near = 0.0f, depth_far = 1.0f;  // depth_range N F
  float point_size = 1.0f;                    // pixels, the side of a 3D point's square
  bool point_sprite = false;                  // point_sprite on: s, t run 0..1 across it
  bool operator==(const ClipState&) const = default;
};

struct CmdViewport { int width = 0, height = 0; };        // viewport W H
struct CmdClear { uint8_t r = 0, g = 0, b = 0; };         // clear colour (A = 255)
struct CmdClearDepth { double z = 1.0; };                 // clear depth in [0, 1]
struct CmdScissor { bool enabled = false; int x = 0, y = 0, width = 0, height = 0; };
struct CmdPrimitives {                                    // tri / strip / fan / tri4 / v4 blocks
  Topology topology = Topology::List;
  std::vector<SceneVertex> vertices;     // screen-space input (tri, v)
  std::vector<ClipVertex> clip_vertices;  // clip-space input (tri4, v4); vertices then empty
  ClipState clip;                         // the front-end state clip_vertices are drawn with
  TextureState texture;                   // the texture bound (none: untextured), ref/texture/texture.h
  bool clip_space() const { return !clip_vertices.empty(); }
};

// ---- 2D drawing (docs/2d.md): each command carries the 2D state it is drawn with ----
struct Style2d {
  std::array<uint8_t, 3> color{}, bgcolor{};  // `color`, `bgcolor` (R G B)
  std::array<uint8_t, 8> pattern{};           // `pattern HEX16`: row 0 first, bit 7 leftmost
  bool pattern_solid = true;                  // `pattern solid` (the initial state)
  uint8_t rop3 = 0;                           // `rop3 XX`
  int point_size = 0;                         // `point_size S`
};
struct Vertex2d { Q64 x, y; };                            // exact decimal pixels
enum class LineTopology { Single, List, Strip, Loop };    // line / lines / linestrip / lineloop
struct Draw2dPoint { Vertex2d p; };
struct Draw2dLines { LineTopology topology = LineTopology::Single; std::vector<Vertex2d> vertices; };
struct Draw2dCircle { int cx = 0, cy = 0, r = 0; bool fill = false; };
struct Draw2dRect { int x = 0, y = 0, w = 0, h = 0; };
struct Draw2dPolygon { std::vector<Vertex2d> vertices; };
struct Draw2dBlit { int sx = 0, sy = 0, dx = 0, dy = 0, w = 0, h = 0; };
struct Draw2dArc { int cx = 0, cy = 0, r = 0; double a0 = 0, a1 = 0; };  // degrees, a1 >= a0
// `font` state (docs/2d-text.md): integer scale, bold (double strike), underline,
// fixed or proportional spacing, transparent or opaque (paper painted with bgcolor).
struct TextStyle {
  int scale = 1;  // 1..16 screen pixels per font pixel, each way
  bool bold = false, underline = false, proportional = false, opaque = false;
  bool operator==(const TextStyle&) const = default;
};
struct Draw2dText {                                       // text x y STRING
  int x = 0, y = 0;                                       // top-left pixel of the first cell
  std::string str;                                        // printable ASCII
  TextStyle style;
};
using Draw2dShape = std::variant<Draw2dPoint, Draw2dLines, Draw2dCircle, Draw2dRect, Draw2dPolygon, Draw2dBlit,
                                 Draw2dArc, Draw2dText>;
struct CmdDraw2d {
  Draw2dShape shape;
  Style2d style;
  const char* keyword = "";  // the trace command, for messages
};

using CommandBody = std::variant<CmdViewport, CmdClear, CmdClearDepth, CmdScissor, CmdPrimitives, CmdDraw2d>;

struct Command {
  CommandBody body;
  SourceLoc loc;
  // > 0: this command is the first of a new frame, and this is the line of the trace's
  // `frame` command (present: the frame before it ends, docs/trace-format.md) that
  // started it. The pipeline does not act on it (a present changes no raster state);
  // the multi-frame runs split the stream here (model/fidelity/frames.h).
  int frame_line = 0;
};

// Every walk of the command stream visits a command through one overload set:
//   visit_command(cmd, Overloaded{[&](const CmdViewport& v) {...}, [&](const CmdClear& c) {...}, ...});
// std::visit needs a handler for every alternative of CommandBody, so a new command type
// stops the build wherever it is not handled. Walkers write no catch-all (`auto`) handler:
// a state command each walker treats alike is still named.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;
template <class V>
decltype(auto) visit_command(const Command& c, V&& visitor) {
  return std::visit(std::forward<V>(visitor), c.body);
}

// Statements a reader read but does not draw or use yet, by keyword, e.g. an OBJ's
// {"vn": 34834, "s": 1} (docs/trace-format.md, "OBJ subset").
using StatementCounts = std::map<std::string, uint64_t>;

struct Scene {
  std::string source;                 // file name
  std::vector<Command> commands;
  StatementCounts obj_ignored;        // an OBJ's (and its MTL files') unused statements
};

}  // namespace rastsim
