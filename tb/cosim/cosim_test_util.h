// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the co-simulation tests (tb/cosim/test_*.cpp): a shipped config by
// name, a scene vertex with random depth and colour, a one-triangle command.
#pragma once

#include <random>
#include <string>

#include "config/config.h"
#include "ref/scene.h"

namespace rastsim::cosim {

inline Config load_shipped_config(const std::string& name) {
  Config c;
  c.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + name + ".toml");
  c.validate();
  return c;
}

// A vertex at (x, y) px with a random depth in [0, 1] and a random colour.
inline SceneVertex random_vertex(double x, double y, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> c8(0, 255);
  std::uniform_real_distribution<double> z(0, 1);
  SceneVertex v;
  v.x = Q64::from_double(x);
  v.y = Q64::from_double(y);
  v.z = z(rng);
  v.r = uint8_t(c8(rng));
  v.g = uint8_t(c8(rng));
  v.b = uint8_t(c8(rng));
  return v;
}

// One triangle as its own command, so a mismatch names its line.
inline Command tri_cmd(const SceneVertex& a, const SceneVertex& b, const SceneVertex& c, const std::string& file,
                       int line) {
  CmdPrimitives p;
  p.vertices = {a, b, c};
  return Command{p, SourceLoc{file, line}};
}

}  // namespace rastsim::cosim
