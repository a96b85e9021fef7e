// SPDX-License-Identifier: Apache-2.0
// A screen-space scene vertex for hand-written and random test scenes.
#pragma once

#include <cstdint>

#include "ref/scene.h"

namespace rastsim {

// Vertex at (x, y) px, depth z in [0, 1], colour (r, g, b).
inline SceneVertex screen_vertex(double x, double y, double z, uint8_t r, uint8_t g = 0, uint8_t b = 0) {
  SceneVertex v;
  v.x = Q64::from_double(x);
  v.y = Q64::from_double(y);
  v.z = z;
  v.r = r;
  v.g = g;
  v.b = b;
  return v;
}

}  // namespace rastsim
