// SPDX-License-Identifier: Apache-2.0
// Attribute interpolation: colour and depth at a pixel centre from barycentric weights.
//
// The weights are the triangle's own edge values at the sample (exact integers in
// raw^2 units, 2F fraction bits): w0 = E1, w1 = E2, w2 = E0, each >= 0 for a covered
// sample, w0 + w1 + w2 = area2. An attribute is
//     attr = round_half_up((w0*a0 + w1*a1 + w2*a2) / area2)
// an exact rational rounded once, so the result lies between the vertex values and is
// the same in every model. Hardware: one divider per attribute with a quotient as wide
// as the attribute (8 bits for colour, raster.depth_bits for depth); widths in
// docs/fixed-point.md. This is interp.method = "plane", the default.
//
// interp.method = "dda" (the lecture notes' incremental spans): along each row the
// covered pixels form one span; its first pixel x0 gets the exact value v0 (the
// rational above) rounded to the DDA's arithmetic, and the x-step s = d attr / d x
// (exact rational: sum of a_k * 2^F * attr_k over area2) is rounded once to it too;
// pixel x0 + k gets v0 + s + s + ... (k additions in that arithmetic), rounded half up
// to the attribute's integer and clamped to its range [0, 2^bits - 1] (8 bits colour,
// raster.depth_bits depth):
//   - f32: IEEE single (v0 and s rounded to nearest from the exact rational);
//   - fixed: interp.dda_frac_bits fraction bits D below the attribute's LSB (v0 and s
//     rounded to nearest, ties to even; k additions are exact, so v = v0 + k s).
// The span's first pixel is found by testing the row's pixel centres from the bounding
// box's left edge (the same exact edge test as traversal), so the value of a pixel does
// not depend on the order in which traversal delivers it.
#pragma once

#include <cstdint>
#include <vector>

#include "ref/tri_setup.h"

namespace rastsim {

struct Fragment {
  int x = 0, y = 0;        // pixel
  uint32_t z = 0;          // unorm raster.depth_bits
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Fragment&) const = default;
};

// The fragment at pixel (px, py) by the triangle's interp_method.
Fragment interpolate(const SetupTriangle& t, int px, int py, int frac_bits);
// The same by plane equations, whatever the triangle's method (the exact reference).
Fragment interpolate_plane(const SetupTriangle& t, int px, int py, int frac_bits);

// One DDA span value: the attribute (bits wide) at step k of a span whose exact start
// value is num0 / den and exact step dnum / den (den > 0), in the given arithmetic.
uint32_t dda_span_value(i128 num0, i128 dnum, i128 den, int64_t k, InterpArith arith, int frac_bits, int bits);
// The values at steps 0..n of the same span, walked once (the stability search on ramps,
// tb/stability/test_interp_dda.cpp): out[k] == dda_span_value(..., k, ...).
void dda_span_values(i128 num0, i128 dnum, i128 den, int64_t n, InterpArith arith, int frac_bits, int bits,
                     std::vector<uint32_t>& out);

}  // namespace rastsim
