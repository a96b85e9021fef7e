// SPDX-License-Identifier: Apache-2.0
#include "ref/interpolate.h"

namespace rastsim {

Fragment interpolate(const SetupTriangle& t, int px, int py, int frac_bits) {
  const int64_t sx = t.sample_x(px, frac_bits), sy = t.sample_y(py, frac_bits);
  // Weight of vertex k is the edge opposite it: edge (k+1)%3 runs between the other two.
  const i128 w[3] = {t.edge[1].eval(sx, sy), t.edge[2].eval(sx, sy), t.edge[0].eval(sx, sy)};
  auto lerp = [&](uint32_t a0, uint32_t a1, uint32_t a2) {
    const i128 num = w[0] * a0 + w[1] * a1 + w[2] * a2;
    return static_cast<uint32_t>(div_round(num, t.area2, Rounding::HalfUp));
  };
  Fragment f;
  f.x = px;
  f.y = py;
  f.z = lerp(t.z[0], t.z[1], t.z[2]);
  f.r = static_cast<uint8_t>(lerp(t.rgb[0][0], t.rgb[1][0], t.rgb[2][0]));
  f.g = static_cast<uint8_t>(lerp(t.rgb[0][1], t.rgb[1][1], t.rgb[2][1]));
  f.b = static_cast<uint8_t>(lerp(t.rgb[0][2], t.rgb[1][2], t.rgb[2][2]));
  return f;
}

}  // namespace rastsim
