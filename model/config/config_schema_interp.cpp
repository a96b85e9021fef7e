// SPDX-License-Identifier: Apache-2.0
// Keys of the attribute interpolation method (docs/stability.md, "Interpolation"):
// exact plane equations (the default) or the lecture notes' incremental span DDA, and
// the DDA's arithmetic. Sweepable like any key.
#include "config/config_schema.h"

namespace rastsim {

void add_interp_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"interp.method", T::Enum, std::string("plane"), "", 1, 0, {"plane", "dda"},
               "Attribute interpolation: plane (exact rational of the edge-function weights a pixel, rounded once) "
               "or dda (the notes' spans: exact value at the span's first pixel, then add the rounded x-step)"});
  s.push_back({"interp.dda_arith", T::Enum, std::string("fixed"), "", 1, 0, {"f32", "fixed"},
               "Arithmetic of the dda interpolation: IEEE single, or fixed point with interp.dda_frac_bits "
               "fraction bits (start value and step rounded to nearest, ties to even)"});
  s.push_back({"interp.dda_frac_bits", T::Int, int64_t{16}, "bits", 1, 32, {},
               "Fraction bits of the fixed-point dda interpolation accumulator (below the attribute's LSB)"});
}

}  // namespace rastsim
