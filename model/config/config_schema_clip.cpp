// SPDX-License-Identifier: Apache-2.0
// Keys of the geometry front end (docs/clip-space.md): how a clip-space triangle that
// crosses the view volume's planes is handled, and the guard band. Sweepable like any key.
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
}

}  // namespace rastsim
