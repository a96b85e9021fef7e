// SPDX-License-Identifier: Apache-2.0
// Co-simulation of the RTL's run-time raster state (label "cosim"): fill rule, cull
// mode and front face are inputs of rast_top (docs/rtl.md), so one verilated model (the
// default config's) runs every combination the config allows, set with the same
// overrides as `rastsim cosim --set raster.fill_rule=... --set raster.cull=...`.
//
// - RasterStateCosim: every fill rule x cull mode x front face (4 x 3 x 2 = 24), each a
//   random scene of ~400 triangles of both windings (quads split along a diagonal,
//   fans around a vertex on a pixel centre, free triangles), edges through pixel
//   centres and shared edges, compared fragment by fragment with the reference model
//   under random backpressure and valid gaps (seeded; the seed is printed).
// - BackFaceCull: triangles culled as back faces produce no fragments and cost setup's
//   interval like any culled triangle (the model's rule: the same cycles as zero-area
//   triangles); the same triangles are drawn when they face front.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <ostream>
#include <random>
#include <utility>

#include "rtlsim/cosim.h"
#include "cosim_test_util.h"
#include "ref/pipeline.h"
#include "config/raster_state_config.h"

namespace rastsim::rtlsim {
namespace {

struct SceneBuilder {
  Scene s;
  std::mt19937_64 rng;
  int line = 0, cw = 0, ccw = 0;
  explicit SceneBuilder(uint64_t seed) : rng(seed) { s.source = "state"; }

  // One triangle as its own command (a mismatch names it); `flip` reverses its winding.
  void tri(double x0, double y0, double x1, double y1, double x2, double y2, bool flip) {
    if (flip) {
      std::swap(x1, x2);
      std::swap(y1, y2);
    }
    const double area2 = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);  // > 0: clockwise on screen
    (area2 > 0 ? cw : ccw) += area2 != 0;
    s.commands.push_back(
        tri_cmd(random_vertex(x0, y0, rng), random_vertex(x1, y1, rng), random_vertex(x2, y2, rng), "state", ++line));
  }
};

// ~n triangles over a w x h viewport, mixed windings. Vertices on pixel centres (k + .5)
// put edges through centres (horizontal, vertical, diagonal), where the fill rule
// decides; quads and fans share every inner edge between two triangles.
Scene state_scene(uint64_t seed, int n, int w, int h, int* cw, int* ccw) {
  SceneBuilder b(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::uniform_int_distribution<int> px(2, w - 18), py(2, h - 18), sz(1, 12);
  auto coin = [&] { return u01(b.rng) < 0.5; };
  while (b.line < n) {
    const double kind = u01(b.rng);
    const double x = px(b.rng) + 0.5, y = py(b.rng) + 0.5;
    if (kind < 0.4) {
      // Quad split along one of its diagonals: two triangles sharing it.
      const double qw = sz(b.rng), qh = sz(b.rng);
      if (coin()) {
        b.tri(x, y, x + qw, y, x, y + qh, coin());
        b.tri(x + qw, y, x + qw, y + qh, x, y + qh, coin());
      } else {
        b.tri(x, y, x + qw, y, x + qw, y + qh, coin());
        b.tri(x, y, x + qw, y + qh, x, y + qh, coin());
      }
    } else if (kind < 0.7) {
      // Fan of 4 to 6 triangles around a centre on a pixel centre; the spokes end on
      // the corners and edge midpoints of a box around it.
      const double r = sz(b.rng) / 2 + 1;
      const double ring[8][2] = {{r, 0}, {r, r}, {0, r}, {-r, r}, {-r, 0}, {-r, -r}, {0, -r}, {r, -r}};
      const int steps = 4 + int(u01(b.rng) * 3);
      const int stride = steps == 4 ? 2 : 1;
      for (int k = 0; k < steps; ++k) {
        const int i = (k * stride) % 8, j = ((k + 1) * stride) % 8;
        b.tri(x, y, x + ring[i][0], y + ring[i][1], x + ring[j][0], y + ring[j][1], coin());
      }
    } else {
      // A free triangle, vertices on a quarter-pixel grid (often exactly on centres).
      std::uniform_real_distribution<double> d(-8, 8);
      auto q = [](double v) { return std::round(v * 4) / 4; };
      b.tri(x, y, q(x + d(b.rng)), q(y + d(b.rng)), q(x + d(b.rng)), q(y + d(b.rng)), coin());
    }
  }
  *cw = b.cw;
  *ccw = b.ccw;
  return b.s;
}

struct StateCase {
  const char* fill;   // raster.fill_rule
  const char* cull;   // raster.cull
  const char* front;  // raster.front_face
  uint64_t seed;      // of the scene and the stress
};
void PrintTo(const StateCase& k, std::ostream* os) {
  *os << "fill_rule=" << k.fill << " cull=" << k.cull << " front_face=" << k.front << " seed=" << k.seed;
}

class RasterStateCosim : public ::testing::TestWithParam<StateCase> {};

TEST_P(RasterStateCosim, MixedWindingsMatchReference) {
  const StateCase& k = GetParam();
  Config cfg = load_shipped_config_fixed_memory("default");
  cfg.apply_override(std::string("raster.fill_rule=") + k.fill);
  cfg.apply_override(std::string("raster.cull=") + k.cull);
  cfg.apply_override(std::string("raster.front_face=") + k.front);
  const uint64_t seed = k.seed;
  std::cout << "seed " << seed << " (scene and stress)\n";
  const int w = static_cast<int>(cfg.get_int("display.width")), h = static_cast<int>(cfg.get_int("display.height"));
  int cw = 0, ccw = 0;
  const Scene scene = state_scene(seed, 400, w, h, &cw, &ccw);
  EXPECT_GT(cw, 100);
  EXPECT_GT(ccw, 100);
  // The reference culls what the state says: facing culls only with a cull mode.
  RenderStats ref;
  render_scene(scene, raster_state_from_config(cfg), ref);
  if (std::string(k.cull) == "none")
    EXPECT_EQ(ref.triangles_facing_culled, 0u);
  else
    EXPECT_GT(ref.triangles_facing_culled, 100u);

  CosimOptions o;
  o.tile_size = 8;
  o.backpressure = 0.2;
  o.valid_gaps = 0.2;
  o.stress_seed = seed;
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg), o);
  std::cout << r.rtl_config << ": " << r.fragments_compared << " fragments, " << r.cycles_rtl << " cycles, "
            << r.wall_seconds << " s\n";
  EXPECT_EQ(r.rtl_config, "default");  // the state is run-time input: no model of its own
  EXPECT_EQ(r.mismatches, 0u) << "first mismatch: " << r.first_mismatch;
  EXPECT_EQ(r.fragments_compared, r.fragments_expected);
  EXPECT_GT(r.fragments_compared, 1000u);
}

std::vector<StateCase> all_states() {
  std::vector<StateCase> v;
  for (const char* fill : {"top_left", "bottom_right", "inclusive", "exclusive"})
    for (const char* cull : {"none", "back", "front"})
      for (const char* front : {"ccw", "cw"}) v.push_back({fill, cull, front, 0x57a7e000u + v.size()});
  return v;
}

std::string camel(const char* s) {
  std::string r;
  bool up = true;
  for (const char* p = s; *p; ++p) {
    if (*p == '_') {
      up = true;
    } else {
      r += up ? char(std::toupper(static_cast<unsigned char>(*p))) : *p;
      up = false;
    }
  }
  return r;
}

INSTANTIATE_TEST_SUITE_P(AllStates, RasterStateCosim, ::testing::ValuesIn(all_states()), [](const auto& info) {
  return camel(info.param.fill) + "Cull" + camel(info.param.cull) + "Front" + camel(info.param.front);
});

// K large clockwise triangles (back faces with front_face = ccw), or K zero-area ones.
Scene repeated(bool zero_area, int k) {
  SceneBuilder b(3);
  for (int i = 0; i < k; ++i) {
    if (zero_area)
      b.tri(10, 10, 50, 50, 100, 100, false);
    else
      b.tri(10.5, 10.5, 100.5, 10.5, 10.5, 100.5, false);  // clockwise on screen
  }
  return b.s;
}

TEST(BackFaceCull, NoFragmentsAndCostOfACulledTriangle) {
  constexpr int kTriangles = 40;
  // The cost of culling in the pipeline's own cycles: the fixed per-access costs (with the
  // config's dram the test took 19 s against 1.4 s on 2 loaded cores).
  Config cull_back = load_shipped_config_fixed_memory("default");
  cull_back.apply_override("raster.cull=back");
  const Scene back = repeated(false, kTriangles), zero = repeated(true, kTriangles);

  const CosimResult culled = run_cosim(back, ArchParams::resolve(cull_back));
  EXPECT_EQ(culled.rtl_config, "default");
  EXPECT_EQ(culled.triangles, uint64_t(kTriangles));
  EXPECT_EQ(culled.fragments_expected, 0u);
  EXPECT_EQ(culled.fragments_compared, 0u);
  EXPECT_EQ(culled.mismatches, 0u) << culled.first_mismatch;
  // Setup spends its interval on a facing-culled triangle as on a zero-area one and
  // hands nothing on: the same cycles, end to end.
  const CosimResult degenerate = run_cosim(zero, ArchParams::resolve(cull_back));
  EXPECT_EQ(degenerate.fragments_compared, 0u);
  EXPECT_EQ(culled.cycles_rtl, degenerate.cycles_rtl);
  // The same triangles culled as front faces (front_face = cw, cull = front) cost the same.
  Config cull_front = cull_back;
  cull_front.apply_override("raster.cull=front");
  cull_front.apply_override("raster.front_face=cw");
  const CosimResult culled_front = run_cosim(back, ArchParams::resolve(cull_front));
  EXPECT_EQ(culled_front.fragments_compared, 0u);
  EXPECT_EQ(culled_front.cycles_rtl, culled.cycles_rtl);
  // Facing front (front_face = cw), they are drawn: every one, and later than culled.
  Config drawn_cfg = cull_back;
  drawn_cfg.apply_override("raster.front_face=cw");
  const CosimResult drawn = run_cosim(back, ArchParams::resolve(drawn_cfg));
  EXPECT_EQ(drawn.mismatches, 0u) << drawn.first_mismatch;
  EXPECT_EQ(drawn.fragments_compared, drawn.fragments_expected);
  EXPECT_GT(drawn.fragments_compared, uint64_t(kTriangles) * 3000);
  EXPECT_GT(drawn.cycles_rtl, culled.cycles_rtl);
}

}  // namespace
}  // namespace rastsim::rtlsim
