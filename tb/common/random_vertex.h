// SPDX-License-Identifier: Apache-2.0
// A random scene vertex on the circle of radius r (pixels) around (x, y), with random
// depth in [0, 1) and random 8-bit colour: the triangle generator the random-scene tests
// share (three of these make a triangle of any winding, sliver or not).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "ref/scene.h"

namespace rastsim::test {

inline SceneVertex random_vertex_on_circle(std::mt19937& rng, double x, double y, double r) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_real_distribution<double> z(0, 1), ang(0, 6.2831853);
  SceneVertex sv;
  const double a = ang(rng);
  sv.x = Q64::from_double(x + r * std::cos(a));
  sv.y = Q64::from_double(y + r * std::sin(a));
  sv.z = z(rng);
  sv.r = uint8_t(byte(rng)), sv.g = uint8_t(byte(rng)), sv.b = uint8_t(byte(rng));
  return sv;
}

}  // namespace rastsim::test
