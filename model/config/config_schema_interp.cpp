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
  // Perspective-correct attributes (docs/clip-space.md).
  s.push_back({"interp.perspective", T::Bool, true, "", 1, 0, {},
               "Interpolate colour and texture coordinates perspective-correctly (a/w and 1/w planes, a reciprocal "
               "a pixel); false: affine in screen space. Screen-space input has 1/w = 1: the same either way"});
  s.push_back({"interp.recip", T::Enum, std::string("newton"), "", 1, 0, {"exact", "newton"},
               "The per-pixel reciprocal of perspective-correct interpolation: newton (a seed table and Newton-Raphson "
               "steps in fixed point, what the RTL builds: rtl/rast_recip.sv) or exact (a rational rounded once, the "
               "golden the others are measured against)"});
  s.push_back({"interp.recip_seed_bits", T::Int, int64_t{8}, "bits", 1, 16, {},
               "Index bits of the newton reciprocal's seed table (2^bits entries)"});
  s.push_back({"interp.recip_iterations", T::Int, int64_t{2}, "", 0, 4, {},
               "Newton-Raphson steps of the newton reciprocal after the seed"});
  s.push_back({"interp.texcoord_format", T::String, std::string("s7.20"), "", 1, 0, {},
               "Interpolated texture coordinate format s<I>.<F> in repeats: I bits of repeat range, F bits of position "
               "within a repeat (a 2^k-texel texture keeps F - k sub-texel bits for bilinear weights)",
               is_fixed_format, "of form s<I>.<F> with I >= 0, F >= 1, I + F <= 31"});
  s.push_back({"interp.color_frac_bits", T::Int, int64_t{8}, "bits", 0, 13, {},
               "Fraction bits of a vertex colour into setup and interpolation (unsigned 8.F a channel): a vertex "
               "clipping makes keeps its binary32 colour rounded once to 2^-F; the pixel's colour is rounded to RGB8 "
               "once, at interpolation. 0: new vertices' colours rounded to RGB8 (13: the RTL's 3 x (8 + F)-bit "
               "colour port fits 64 bits)"});
  // The reciprocal unit's throughput (docs/clip-space.md, "Timing"; TimingParams::interp_lanes).
  s.push_back({"recip.lanes", T::Int, int64_t{4}, "reciprocals/cycle", 1, 1024, {},
               "Reciprocals the interpolator computes per cycle: a perspective-correct (non-affine) triangle's "
               "pixels are interpolated min(interp.fragments_per_cycle, recip.lanes) a cycle (interp.perspective = "
               "true only; affine triangles keep interp.fragments_per_cycle)"});
}

}  // namespace rastsim
