// SPDX-License-Identifier: Apache-2.0
// The reference 2D engine, in two halves that every level shares (docs/2d.md):
//
// - The front end, draw2d_ops: one CmdDraw2d (ref/scene.h) into a list of engine
//   operations (Op2d) with the geometry of line_raster, point_raster, circle_raster,
//   polygon_fill and text_raster. It reads no pixel.
// - The engine, execute_op2d: one operation on the framebuffer through the pattern and
//   ROP3 (ref/2d/raster2d.h). The SystemC engine2d stage and the RTL rast_engine2d execute
//   the same operations; their cost equations are on TimingParams.
//
// - Coordinates of points, lines and polygons are snapped like triangle vertices
//   (raster.coord_format, round to nearest even, relative to the viewport centre), so
//   the same range check applies: outside the format is an error naming the line, or
//   with raster.out_of_range = cull the primitive is dropped and counted.
// - Everything is clipped to the viewport, the framebuffer and the scissor; 2D pixels
//   bypass the depth test and write colour only (alpha 255).
#pragma once

#include <cstdint>
#include <vector>

#include "ref/framebuffer.h"
#include "ref/2d/raster2d.h"
#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

struct Draw2dStats {
  uint64_t primitives = 0;         // 2D commands drawn
  uint64_t primitives_culled = 0;  // dropped: a coordinate outside the format (cull mode)
  uint64_t pixels = 0;             // pixels written (after clipping)
};

// One operation of the 2D engine.
struct Op2d {
  enum class Kind : uint8_t {
    Span,   // row y0, pixels [x0, x1), already clipped and never empty
    Pixel,  // one pixel (x0, y0), clipped by the engine (diamond and DDA lines, in order)
    Line,   // index-method line from pixel (x0, y0) to (x1, y1), both ends drawn, walked
            // by the line unit (Bresenham, or midpoint when `midpoint`), each pixel clipped
    Blit,   // w x h from source (sx, sy) to destination (x0, y0), already clipped, never
            // empty, walked in the overlap-safe order of blit_walk_order
  };
  // What a Span takes as its pattern operand P: the current pattern (fg where its bit is
  // 1, bg where 0), or the foreground or background colour everywhere (text cells).
  enum class Paint : uint8_t { Pattern, Foreground, Background };

  Kind kind = Kind::Span;
  Paint paint = Paint::Pattern;
  bool midpoint = false;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int sx = 0, sy = 0, w = 0, h = 0;

  bool operator==(const Op2d&) const = default;
};

// What the front end hands the engine for one command.
struct Draw2dWork {
  Raster2dState paint;     // colours, pattern, ROP3 code
  PixelRect clip;          // viewport & scissor & framebuffer
  std::vector<Op2d> ops;   // in drawing order
  bool culled = false;     // dropped (raster.out_of_range = cull): no ops
};

// Front end: the operations of one 2D command at the state `st` (viewport, scissor,
// formats, line method, polygon rule) on a fb_width x fb_height framebuffer. Throws
// SceneError naming `loc` for a coordinate outside the format.
Draw2dWork draw2d_ops(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st);

// Vertices a 2D command brings from memory (points, lines, polygons; a text's string as
// one vertex-sized word per 8 characters; 0 for the shapes whose integers travel in the
// command header).
uint64_t draw2d_vertex_count(const CmdDraw2d& cmd);

// Engine: executes one operation. Returns the pixels written. `mem`: the colour
// surface's memory client its accesses go through (raster2d.h; null: none counted).
uint64_t execute_op2d(Framebuffer& fb, const Draw2dWork& work, const Op2d& op, SurfaceClient* mem = nullptr);

// Both halves: draws one 2D command and counts it.
void draw_2d(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Framebuffer& fb, Draw2dStats& stats,
             SurfaceClient* mem = nullptr);

}  // namespace rastsim
