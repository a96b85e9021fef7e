// SPDX-License-Identifier: Apache-2.0
// The reference 2D engine: one CmdDraw2d (ref/scene.h) into the framebuffer, with the
// geometry of line_raster, point_raster, circle_raster and polygon_fill and the pixel
// operations of raster2d (pattern, ROP3, blit). docs/2d.md states the rules.
//
// - Coordinates of points, lines and polygons are snapped like triangle vertices
//   (raster.coord_format, round to nearest even, relative to the viewport centre), so
//   the same range check applies: outside the format is an error naming the line, or
//   with raster.out_of_range = cull the primitive is dropped and counted.
// - Everything is clipped to the viewport, the framebuffer and the scissor; 2D pixels
//   bypass the depth test and write colour only (alpha 255).
#pragma once

#include <cstdint>

#include "ref/framebuffer.h"
#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

struct Draw2dStats {
  uint64_t primitives = 0;       // 2D commands drawn
  uint64_t primitives_culled = 0;  // dropped: a coordinate outside the format (cull mode)
  uint64_t pixels = 0;           // pixels written (after clipping)
};

// Draws one 2D command. Throws SceneError naming `loc` for a coordinate outside the format.
void draw_2d(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Framebuffer& fb, Draw2dStats& stats);

}  // namespace rastsim
