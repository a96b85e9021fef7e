// SPDX-License-Identifier: Apache-2.0
// Keys of the 2D primitives (docs/2d.md): the line rasterization method and its
// arithmetic, and the polygon fill rule. Sweepable like any key.
#include "config/config_schema.h"

namespace rastsim {

void add_2d_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"line.method", T::Enum, std::string("diamond"), "", 1, 0, {"diamond", "bresenham", "midpoint", "dda"},
               "Line rasterization: diamond (D3D11/OpenGL diamond exit on snapped endpoints); bresenham, midpoint, "
               "dda (the notes' algorithms on pixel indices, both end pixels drawn)"});
  s.push_back({"line.dda_arith", T::Enum, std::string("fixed"), "", 1, 0, {"f32", "f64", "fixed"},
               "Arithmetic of the dda line method: IEEE single, double, or fixed point with the fraction bits of "
               "raster.coord_format"});
  s.push_back({"polygon.rule", T::Enum, std::string("even_odd"), "", 1, 0, {"even_odd", "nonzero"},
               "Polygon fill rule: even_odd (the notes' odd parity) or nonzero (winding)"});
}

}  // namespace rastsim
