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
// docs/fixed-point.md.
#pragma once

#include <cstdint>

#include "ref/tri_setup.h"

namespace rastsim {

struct Fragment {
  int x = 0, y = 0;        // pixel
  uint32_t z = 0;          // unorm raster.depth_bits
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Fragment&) const = default;
};

Fragment interpolate(const SetupTriangle& t, int px, int py, int frac_bits);

}  // namespace rastsim
