// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the co-simulation tests (tb/cosim/test_*.cpp): a shipped config by
// name, a scene vertex with random depth and colour, a one-triangle command, random
// scenes, the clean-run check.
#pragma once

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "config/config.h"
#include "ref/scene.h"
#include "rtlsim/cosim.h"

namespace rastsim::rtlsim {

inline Config load_shipped_config(const std::string& name) {
  Config c;
  c.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + name + ".toml");
  c.validate();
  return c;
}

// The shipped config with memory.model = fixed, for tests of the raster's arithmetic
// (random and directed scenes under backpressure: fragments, masks and CRCs against the
// reference): with the configs' own dram the RTL would also run every DRAM wait, 2-10x
// the cycles (minutes a test on CI's 2 cores). The RTL through the DRAM model is tested
// with the configs' dram by ctest cosim.cycles.*, cosim.3d.*, cosim.msaa.*, cosim.state.*,
// cosim.stress.* and the stage-by-stage tests (test_stages.cpp).
inline Config load_shipped_config_fixed_memory(const std::string& name) {
  Config c = load_shipped_config(name);
  c.apply_override("memory.model=fixed");
  c.validate();
  return c;
}

// A vertex at (x, y) px with a random depth in [0, 1] and a random colour; with
// color_frac_bits F > 0 the colour is a random unsigned 8.F (as a vertex clipping made:
// its fraction bits exercise the affine colour dividers' shifted denominator).
inline SceneVertex random_vertex(double x, double y, std::mt19937_64& rng, int color_frac_bits = 0) {
  std::uniform_int_distribution<int> c8(0, 255);
  std::uniform_real_distribution<double> z(0, 1);
  SceneVertex v;
  v.x = Q64::from_double(x);
  v.y = Q64::from_double(y);
  v.z = z(rng);
  v.r = uint8_t(c8(rng));
  v.g = uint8_t(c8(rng));
  v.b = uint8_t(c8(rng));
  const uint8_t rgb8[3] = {v.r, v.g, v.b};  // a channel of 255 has no fraction (8.F is at most 255)
  for (size_t c = 0; c < 3; ++c)
    v.rgb_frac[c] = color_frac_bits > 0 && rgb8[c] < 255 ? uint16_t(rng() % (1u << color_frac_bits)) : 0;
  return v;
}

// One triangle as its own command, so a mismatch names its line.
inline Command tri_cmd(const SceneVertex& a, const SceneVertex& b, const SceneVertex& c, const std::string& file,
                       int line) {
  CmdPrimitives p;
  p.vertices = {a, b, c};
  return Command{p, SourceLoc{file, line}};
}

// A directed scene built a triangle at a time, each its own command (random depth and
// colour) so a mismatch names its line; state commands in between.
struct DirectedScene {
  Scene scene;
  std::mt19937_64 rng;
  int line = 0;
  DirectedScene(const std::string& name, uint64_t seed) : rng(seed) { scene.source = name; }
  void add(double x0, double y0, double x1, double y1, double x2, double y2) {
    scene.commands.push_back(tri_cmd(random_vertex(x0, y0, rng), random_vertex(x1, y1, rng),
                                     random_vertex(x2, y2, rng), scene.source, ++line));
  }
  void state(CommandBody body) { scene.commands.push_back(Command{std::move(body), SourceLoc{scene.source, ++line}}); }
};

// Random triangles over the viewport and its guard band: mostly small, some large,
// some slivers and some degenerate, colours with the config's interp.color_frac_bits;
// now and then a scissor or viewport change.
inline Scene random_scene(const Config& cfg, uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  const int w = static_cast<int>(cfg.get_int("display.width")), h = static_cast<int>(cfg.get_int("display.height"));
  const FixedFormat fmt = FixedFormat::parse(cfg.get_string("raster.coord_format"));
  const double guard = std::min(fmt.to_double(fmt.raw_max()) - w / 2.0, 48.0);  // stay inside the format
  std::uniform_real_distribution<double> ux(-guard * 0.5, w + guard * 0.5), uy(-guard * 0.5, h + guard * 0.5);
  std::uniform_real_distribution<double> u01(0, 1);
  const int frac_steps = 1 << std::min(fmt.frac_bits, 8);
  auto q = [&](double v) { return std::round(v * frac_steps) / frac_steps; };  // often exactly on samples
  const int cf = static_cast<int>(cfg.get_int("interp.color_frac_bits"));       // colours unsigned 8.cf
  Scene s;
  s.source = "random";
  int line = 0;
  for (int k = 0; k < n; ++k) {
    ++line;
    const double kind = u01(rng);
    if (kind < 0.01) {
      CmdScissor sc;
      sc.enabled = u01(rng) < 0.5;
      sc.x = int(u01(rng) * w / 2);
      sc.y = int(u01(rng) * h / 2);
      sc.width = int(u01(rng) * w / 2) + 1;
      sc.height = int(u01(rng) * h / 2) + 1;
      s.commands.push_back(Command{sc, SourceLoc{"random", line}});
      continue;
    }
    const double cx = q(ux(rng)), cy = q(uy(rng));
    const double size = kind < 0.7 ? 6.0 : (kind < 0.9 ? 24.0 : 64.0);
    std::uniform_real_distribution<double> d(-size, size);
    SceneVertex a = random_vertex(cx, cy, rng, cf), b = random_vertex(q(cx + d(rng)), q(cy + d(rng)), rng, cf),
                c = random_vertex(q(cx + d(rng)), q(cy + d(rng)), rng, cf);
    if (kind > 0.97)
      c = random_vertex(q(2 * b.x.to_double() - a.x.to_double()), q(2 * b.y.to_double() - a.y.to_double()), rng, cf);
    s.commands.push_back(tri_cmd(a, b, c, "random", line));
  }
  return s;
}

// A random scene of `triangles` through the RTL at tile size `tile` with 30 % random
// backpressure and 30 % gaps in the triangle valid; `seed` (printed) seeds all three.
inline CosimResult run_random_scene(const Config& cfg, uint64_t seed, int triangles, int tile) {
  std::cout << "seed " << seed << " (scene, backpressure and valid gaps)\n";
  const Scene scene = random_scene(cfg, seed, triangles);
  CosimOptions o;
  o.tile_size = tile;
  o.backpressure = 0.3;
  o.valid_gaps = 0.3;
  o.stress_seed = seed;
  return run_cosim(scene, ArchParams::resolve(cfg), o);
}

inline void expect_clean(const CosimResult& r) {
  EXPECT_EQ(r.mismatches, 0u) << "first mismatch: " << r.first_mismatch;
  EXPECT_EQ(r.fragments_compared, r.fragments_expected);
  EXPECT_GT(r.cycles_rtl, 0u);
}

}  // namespace rastsim::rtlsim
