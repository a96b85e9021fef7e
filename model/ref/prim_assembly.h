// SPDX-License-Identifier: Apache-2.0
// Primitive assembly: triangle lists, strips and fans into independent triangles.
//
// - List: vertices (3k, 3k+1, 3k+2).
// - Strip: triangle k is (k, k+1, k+2) for even k and (k+1, k, k+2) for odd k, so every
//   triangle of a strip keeps the winding of the first (OpenGL/Direct3D order).
// - Fan: triangle k is (0, k+1, k+2).
//
// A clip-space command (tri4, v4: CmdPrimitives::clip_space) goes through the geometry
// front end (front_end.h), which clips, divides by w and maps to the viewport;
// for_each_triangle is the one entry every walker of the reference model draws through.
#pragma once

#include <array>
#include <cstddef>

#include "ref/front_end.h"
#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

// Number of triangles `vertices` vertices of a triangle topology make (0 for points and lines).
size_t triangle_count(Topology t, size_t vertices);
// Indices of triangle k's vertices (a triangle topology).
std::array<size_t, 3> triangle_indices(Topology t, size_t k);

// Number of triangles a screen-space primitive command makes (0 for a clip-space one).
size_t triangle_count(const CmdPrimitives& p);
// Vertices of triangle k of a screen-space command.
std::array<SceneVertex, 3> assemble_triangle(const CmdPrimitives& p, size_t k);

// Calls fn(const ScreenTriangle&) for every screen-space triangle the command makes, in
// order: a screen-space command's as assemble_triangle gives them, a clip-space command's
// out of the front end under the current state `st` (counted into `stats`; it throws
// SceneError naming `loc` as front_end does).
template <class Fn>
void for_each_triangle(const CmdPrimitives& p, const RasterState& st, const SourceLoc& loc, FrontEndStats& stats,
                       Fn&& fn) {
  if (p.clip_space()) {
    front_end(p, st, loc, stats, [&fn](const ScreenTriangle& t) { fn(t); });
    return;
  }
  const size_t n = triangle_count(p);
  for (size_t k = 0; k < n; ++k) fn(assemble_triangle(p, k));
}

// For the levels that have no front end yet (SystemC, RTL testbench): throws SceneError
// naming `loc` when `p` is a clip-space command, so that none is silently not drawn.
void reject_clip_space(const CmdPrimitives& p, const SourceLoc& loc);

}  // namespace rastsim
