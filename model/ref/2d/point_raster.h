// SPDX-License-Identifier: Apache-2.0
// Points: a square of side `size` pixels centred on the snapped point (x, y) (raw
// fixed point with `frac_bits` fraction bits, absolute pixel coordinates), drawn as
// the pixels whose centres lie inside it, top-left rule on its edges: a centre on the
// left or top edge is inside, on the right or bottom edge outside. So points of size S
// at S-pixel spacing tile the plane, each pixel once.
#pragma once

#include <cstdint>

#include "ref/raster_state.h"

namespace rastsim {

// The pixels [x0, x1) x [y0, y1) the point covers (empty for size 0).
inline PixelRect point_pixels(int64_t x, int64_t y, int size, int frac_bits) {
  // Centre of pixel p: p * 2^F + 2^(F-1). Inside [c - s/2, c + s/2) <=> p in
  // [ceil((c - s/2 - 1/2) / 1), ceil((c + s/2 - 1/2) / 1)), in raw units (2^F = 1 px).
  const int64_t one = int64_t{1} << frac_bits, half = one / 2, hs = int64_t(size) * half;
  auto ceil_div = [](int64_t a, int64_t b) { return (a >= 0) ? (a + b - 1) / b : -((-a) / b); };
  return PixelRect{int(ceil_div(x - hs - half, one)), int(ceil_div(y - hs - half, one)),
                   int(ceil_div(x + hs - half, one)), int(ceil_div(y + hs - half, one))};
}

}  // namespace rastsim
