// SPDX-License-Identifier: Apache-2.0
// Keys of the geometry front end (docs/clip-space.md): how a clip-space triangle that
// crosses the view volume's planes is handled, the guard band, and the timed stage's
// costs and FIFOs (TimingParams::front_end_*; docs/microarchitecture.md). Sweepable like
// any key.
#include "config/config_schema.h"

namespace rastsim {

void add_clip_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"clip.method", T::Enum, std::string("clip"), "", 1, 0, {"clip", "homogeneous"},
               "Clip-space triangles: clip (Sutherland-Hodgman against near, far and, outside the guard band, "
               "x/y planes, then divide by w) or homogeneous (2D-homogeneous rasterization of triangles, no new "
               "vertices; rastsim render only, the other levels stop with a scene error)"});
  s.push_back({"clip.guard_band", T::Float, 1.0, "viewports", 1.0, 64.0, {},
               "Guard band: x and y are clipped only where a vertex lies outside +-g w (g times the viewport "
               "around its centre); the snapped coordinates must fit raster.coord_format"});
  // ---- the timed stage (SystemC: sc/front_end.h) ----
  s.push_back({"front_end.cycles_per_primitive", T::Int, int64_t{1}, "cycles", 1, 1024, {},
               "Geometry front end: cycles of one clip-space primitive's plane tests and cull decision (a "
               "triangle, point or line segment; culled ones too)"});
  s.push_back({"front_end.clip_cycles_per_vertex", T::Int, int64_t{2}, "cycles", 1, 1024, {},
               "Geometry front end: cycles for each vertex clipping makes (t = d_a / (d_a - d_b) and the "
               "interpolation of x y z w s t and colour)"});
  s.push_back({"front_end.vertices_per_cycle", T::Int, int64_t{1}, "vertices/cycle", 1, 64, {},
               "Geometry front end: divide and viewport lanes; a triangle out takes ceil(n / this) for its new "
               "vertices (3 for the first of a primitive, 1 for each later one)"});
  s.push_back({"front_end.latency_cycles", T::Int, int64_t{4}, "cycles", 0, 4096, {},
               "Geometry front end: pipeline latency of the divide and viewport transform (1/w, x * q, scale, "
               "offset: rtl/rast_front_end_xform is 4); a triangle is ready downstream this much after its issue"});
  s.push_back({"fifo.clip_command_depth", T::Int, int64_t{2}, "entries", 1, 65536, {},
               "Command fetch -> geometry front end FIFO (one entry: a clip-space command)"});
  s.push_back({"fifo.screen_depth", T::Int, int64_t{4}, "entries", 1, 65536, {},
               "Geometry front end -> primitive assembly FIFO (one entry: a screen-space triangle or the end of a "
               "command), plus front_end.latency_cycles pipeline slots"});
}

}  // namespace rastsim
