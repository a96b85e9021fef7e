// SPDX-License-Identifier: Apache-2.0
// The geometry front end (stage `front_end`, docs/clip-space.md): one clip-space
// primitive of a CmdPrimitives into screen-space triangles of SceneVertex, which triangle
// setup snaps as it snaps a `tri` vertex.
//
// - Triangles (List, Strip, Fan): culled when behind the eye (w <= 0 at every vertex) or
//   outside one plane of the guard-band volume; otherwise Sutherland-Hodgman clipped
//   against near (z >= 0), far (z <= w), x = -+g w, y = -+g w (g = clip.guard_band, a
//   plane no vertex lies outside leaves the polygon as it is), divided by w, mapped to
//   the viewport and fanned from the polygon's first vertex.
// - Points: culled unless the vertex lies inside that volume, then a screen-aligned square
//   of side point_size (two triangles). Lines: each segment clipped like a triangle's edge,
//   then a 1-pixel-wide quad (GL's aliased-line rule, two triangles).
//
// Every clip-space value is IEEE binary32 in the operation order docs/clip-space.md
// states; this file is compiled with -ffp-contract=off (no fused multiply-add).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

// What the front end did, by the names of the stats JSON (docs/stats.md).
struct FrontEndStats {
  uint64_t clip_triangles_in = 0;         // clip-space triangles assembled (before clipping)
  uint64_t triangles_behind = 0;          // w <= 0 at every vertex: culled
  uint64_t triangles_culled_outside = 0;  // every vertex outside one plane, or clipped to nothing
  uint64_t triangles_clipped = 0;         // a plane cut them: a new polygon
  uint64_t clip_vertices_made = 0;        // vertices clipping made (triangles and line segments)
  uint64_t triangles_nonfinite = 0;       // dropped: 1/w or the viewport map overflowed binary32
  uint64_t clip_triangles_out = 0;        // screen-space triangles out to setup (points and lines too)
  uint64_t points_in = 0, points_culled = 0;                    // 3D points; culled: outside the volume
  uint64_t lines_in = 0, lines_culled = 0, lines_clipped = 0;  // 3D line segments
  bool any() const { return clip_triangles_in + points_in + lines_in > 0; }
};

using ScreenTriangle = std::array<SceneVertex, 3>;
using ScreenTriangleSink = std::function<void(const ScreenTriangle&)>;

// The viewport map of one primitive (docs/clip-space.md, "Operation order"), its binary32
// constants computed once: W/2, X + W/2, H/2, Y + H/2, F - N, N.
struct ViewportMap {
  float half_w = 0, centre_x = 0, half_h = 0, centre_y = 0, depth_scale = 0, depth_near = 0;
  float depth_lo = 0, depth_hi = 0;  // min(N, F), max(N, F): the clamp of z_w
};
// The map of `clip` under the current viewport (the default viewport_xform).
ViewportMap viewport_map(const ClipState& clip, const RasterState& st);

// Divide by w and viewport transform of a vertex with w > 0; z_w is clamped to the depth
// range (binary32 rounding can put a clipped vertex an ulp beyond near or far). The
// binary32 colour is rounded once to unsigned 8.F (F = color_frac_bits,
// interp.color_frac_bits; round_colour). Returns false when a result is not finite (1/w
// overflowed).
bool to_screen(const ClipVertex& v, const ViewportMap& m, int color_frac_bits, SceneVertex& out);
// A binary32 colour channel c in [0, 255] as unsigned 8.F: c 2^F (exact) rounded to the
// nearest integer, ties to even, clamped to [0, 255 2^F]. An integer c gives c 2^F.
uint32_t round_colour(float c, int color_frac_bits);

// The guard-band volume's planes in clipping order, and the signed binary32 distance of
// a vertex from each (>= 0: inside).
enum class ClipPlane { Near, Far, Left, Right, Top, Bottom };
inline constexpr std::array<ClipPlane, 6> kClipPlanes{ClipPlane::Near, ClipPlane::Far,  ClipPlane::Left,
                                                      ClipPlane::Right, ClipPlane::Top, ClipPlane::Bottom};
float plane_distance(const ClipVertex& v, ClipPlane p, float guard_band);
// The point where segment (inside, outside) crosses plane p, interpolated from the end
// nearer the plane (no cancellation), a choice of the edge alone, so that both triangles
// of a shared edge make the same vertex bit for bit.
ClipVertex clip_intersection(const ClipVertex& inside, const ClipVertex& outside, ClipPlane p, float guard_band);

// Sutherland-Hodgman: a triangle's clipped polygon (empty when nothing is left), counting
// new vertices into stats.clip_vertices_made; `clipped` says whether a plane cut it.
std::vector<ClipVertex> clip_triangle(const std::array<ClipVertex, 3>& tri, float guard_band, FrontEndStats& stats,
                                      bool& clipped);

// Throws SceneError naming `loc` when a clip-space value of `p` is not a finite binary32.
void check_clip_space_finite(const CmdPrimitives& p, const SourceLoc& loc);

// The front end over one clip-space command (p.clip_space()): every screen-space
// triangle it makes, in order, to `emit`. Throws SceneError naming `loc` for a
// non-finite clip-space value and for triangles under clip.method = homogeneous, which
// only the reference renderer draws (ref/homogeneous.h; its points and lines come here).
void front_end(const CmdPrimitives& p, const RasterState& st, const SourceLoc& loc, FrontEndStats& stats,
               const ScreenTriangleSink& emit);

}  // namespace rastsim
