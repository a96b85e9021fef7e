// SPDX-License-Identifier: Apache-2.0
// Co-simulation tests (label "cosim"): the verilated RTL against the reference model,
// every fragment compared bit for bit, in order (tb/cosim/cosim.h).
//
// - Random scenes of 2,000 triangles for three tile sizes (4, 8, 16: the RTL's tile size
//   is a run-time input) and two coordinate formats (default s7.16, d3d11 s15.8), with
//   random backpressure on the ROP's memory port and gaps in the triangle valid (seeded;
//   the seed is printed).
// - Directed scenes: fill-rule edges through pixel centres, slivers, degenerate
//   (zero-area, collinear, repeated vertex) triangles, triangles crossing and touching
//   the viewport border and the guard band, vertices at the format's extreme values,
//   state changes (viewport, scissor) between triangles.
// - Stress on every valid/ready input of the RTL (memory-port backpressure, gaps in
//   tri_valid_i and the 2D engine's in_valid_i; seeded, the seed printed): the same
//   fragments and image as without, in more cycles; the same seed replays the same run.
// - 120 random clip-space triangles (tri4 with colour and texture coordinates, near-plane
//   crossings, 1/w spread over up to 2^8) with every shipped config, one and four samples
//   (msaa: extrapolated centres, D <= 0 and clamping) and backpressure: the perspective-
//   correct interpolator (rtl/rast_interpolate_persp.sv) and the affine texture
//   coordinates against the reference with interp.recip = newton, fragment for fragment.
//   interp.recip = exact with a perspective-correct triangle is refused, naming the line.
// - The shipped scenes with each shipped config run as the ctests cosim.cycles.* through
//   `rastsim cosim` (fragments and the cycle comparison with the SystemC model).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "rtlsim/cosim.h"
#include "scene/scene_io.h"
#include "timing/stage_table.h"
#include "cosim_test_util.h"

namespace rastsim::rtlsim {
namespace {

struct RandomCase {
  const char* config;
  int tile;
};
class RandomCosim : public ::testing::TestWithParam<RandomCase> {};

TEST_P(RandomCosim, TwoThousandTrianglesWithBackpressure) {
  Config cfg = load_shipped_config_fixed_memory(GetParam().config);
  cfg.apply_override("raster.out_of_range=cull");  // some vertices leave the guard band
  const uint64_t seed = 0x5eed0000u + uint64_t(GetParam().tile);
  const CosimResult r = run_random_scene(cfg, seed, 2000, GetParam().tile);
  std::cout << r.fragments_compared << " fragments, " << r.cycles_rtl << " cycles, " << r.wall_seconds << " s\n";
  expect_clean(r);
  EXPECT_GT(r.fragments_compared, 10000u);
}

INSTANTIATE_TEST_SUITE_P(Formats, RandomCosim,
                         ::testing::Values(RandomCase{"default", 4}, RandomCase{"default", 8},
                                           RandomCase{"default", 16}, RandomCase{"d3d11", 4},
                                           RandomCase{"d3d11", 8}, RandomCase{"d3d11", 16}),
                         [](const auto& info) {
                           return std::string(info.param.config) + "Tile" + std::to_string(info.param.tile);
                         });

// Directed triangles, each pushed as its own command so a mismatch names it.
Scene directed_scene(const Config& cfg) {
  const int w = static_cast<int>(cfg.get_int("display.width")), h = static_cast<int>(cfg.get_int("display.height"));
  const FixedFormat fmt = FixedFormat::parse(cfg.get_string("raster.coord_format"));
  const double ox = w / 2, oy = h / 2;
  const double min_px = ox + fmt.to_double(fmt.raw_min()), max_px = ox + fmt.to_double(fmt.raw_max());
  const double min_py = oy + fmt.to_double(fmt.raw_min()), max_py = oy + fmt.to_double(fmt.raw_max());
  DirectedScene d("directed", 7);
  auto add = [&](double x0, double y0, double x1, double y1, double x2, double y2) { d.add(x0, y0, x1, y1, x2, y2); };
  // Fill rule: shared edges through pixel centres, all eight orientations of a square.
  add(8.5, 8.5, 40.5, 8.5, 8.5, 40.5);
  add(40.5, 8.5, 40.5, 40.5, 8.5, 40.5);
  add(8.5, 8.5, 8.5, 40.5, 40.5, 8.5);
  add(40.5, 8.5, 8.5, 40.5, 40.5, 40.5);
  add(20.5, 20.5, 30.5, 20.5, 25.5, 30.5);  // horizontal top edge on centres
  add(20.5, 30.5, 25.5, 20.5, 30.5, 30.5);  // horizontal bottom edge on centres
  add(50.5, 10.5, 50.5, 30.5, 60.5, 20.5);  // vertical left edge
  add(60.5, 10.5, 50.5, 20.5, 60.5, 30.5);  // vertical right edge
  // Slivers: long and thin in every direction, and sub-pixel ones.
  add(1, 1, w - 1, 2, w - 1, 2.25);
  add(1, 1, 1.3, h - 1, 1.1, h - 1);
  add(0.5, 0.5, w - 0.5, h - 0.5, w - 0.4, h - 0.5);
  add(10.1, 10.1, 10.2, 10.9, 10.3, 10.15);
  // Degenerate: zero area (collinear, repeated vertex, all equal).
  add(5, 5, 10, 10, 20, 20);
  add(5, 5, 5, 5, 20, 7);
  add(9, 9, 9, 9, 9, 9);
  // Viewport border: crossing each side, touching it, covering all of it.
  add(-20, -20, w / 2.0, 10, 10, h / 2.0);
  add(w + 20, h + 20, w / 2.0, h - 10, w - 10, h / 2.0);
  add(0, 0, w, 0, 0, h);
  add(w, 0, w, h, 0, h);
  add(-1, h / 2.0, w + 1, h / 2.0 - 3, w + 1, h / 2.0 + 3);
  // Maximum range: vertices at the format's extreme raw values (guard band corners).
  add(min_px, min_py, max_px, min_py, min_px, max_py);
  add(max_px, min_py, max_px, max_py, min_px, max_py);
  add(min_px, min_py, max_px, max_py, max_px, min_py);
  add(min_px, oy, ox, min_py, max_px, max_py);
  // State: a smaller viewport (new origin), scissor on and off.
  d.state(CmdViewport{w / 2, h / 2});
  add(1, 1, w / 2.0 - 1, 3, 5, h / 2.0 - 1);
  d.state(CmdScissor{true, 4, 4, 20, 12});
  add(0, 0, w / 2.0, 0, 0, h / 2.0);
  d.state(CmdScissor{false, 0, 0, 0, 0});
  d.state(CmdViewport{w, h});
  add(3, 3, 50, 7, 9, 60);
  return d.scene;
}

struct DirectedCase {
  const char* config;
  int tile;
};
class DirectedCosim : public ::testing::TestWithParam<DirectedCase> {};

TEST_P(DirectedCosim, EdgeCasesMatch) {
  // The raster's edge cases (with the configs' dram, d3d11 at 4 px tiles took over 150 s).
  const Config cfg = load_shipped_config_fixed_memory(GetParam().config);
  CosimOptions o;
  o.tile_size = GetParam().tile;
  o.backpressure = 0.5;
  o.valid_gaps = 0.5;
  o.stress_seed = 11;
  const CosimResult r = run_cosim(directed_scene(cfg), ArchParams::resolve(cfg), o);
  expect_clean(r);
}

INSTANTIATE_TEST_SUITE_P(Configs, DirectedCosim,
                         ::testing::Values(DirectedCase{"default", 2}, DirectedCase{"default", 16},
                                           DirectedCase{"d3d11", 4}, DirectedCase{"embedded", 8}),
                         [](const auto& info) {
                           return std::string(info.param.config) + "Tile" + std::to_string(info.param.tile);
                         });

// A scene with triangles, state commands and 2D commands, so that every valid/ready
// input of the RTL carries traffic.
Scene mixed_scene(const Config& cfg, uint64_t seed) {
  Scene s = random_scene(cfg, seed, 600);
  Style2d style;
  style.color = {200, 40, 90};
  style.rop3 = 0xF0;  // PATCOPY: the colour
  const auto v = [](double x, double y) { return Vertex2d{Q64::from_double(x), Q64::from_double(y)}; };
  const CmdDraw2d rect{Draw2dRect{4, 6, 40, 20}, style, "rect"};
  const CmdDraw2d lines{Draw2dLines{LineTopology::Strip, {v(2, 3), v(90, 70), v(10, 60)}}, style, "linestrip"};
  for (size_t k = 0; k < 6; ++k) {
    const auto at = s.commands.begin() + std::ptrdiff_t(k * 100);
    s.commands.insert(at, Command{k % 2 ? CommandBody{lines} : CommandBody{rect}, SourceLoc{"mixed", int(k)}});
  }
  return s;
}

// `scene` under backpressure 0.3 and valid gaps 0.3 (seeded by `seed`): clean, every
// fragment, 2D pixel and the image as in the `calm` run, more cycles; returns the options.
CosimOptions expect_stress_keeps(const Scene& scene, const Config& cfg, const CosimResult& calm, uint64_t seed) {
  CosimOptions o;
  o.backpressure = 0.3;
  o.valid_gaps = 0.3;
  o.stress_seed = seed;
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg), o);
  expect_clean(r);
  EXPECT_EQ(r.fragments_compared, calm.fragments_compared);
  EXPECT_EQ(r.pixels_2d, calm.pixels_2d);
  EXPECT_EQ(r.crc_rtl, calm.crc_rtl);
  EXPECT_GT(r.cycles_rtl, calm.cycles_rtl) << "the stress held inputs back";
  return o;
}

TEST(StressCosim, ValidGapsAndBackpressureKeepEveryFragment) {
  Config cfg = load_shipped_config("default");
  cfg.apply_override("raster.out_of_range=cull");
  // The fixed per-access costs: the stages' cycle counts below without DRAM stalls
  // (the DRAM model under the same stress: DramStressKeepsTheTwoDEngineExact).
  cfg.apply_override("memory.model=fixed");
  const uint64_t seed = 0x57e55000u;
  std::cout << "seed " << seed << " (scene and stress)\n";
  const Scene scene = mixed_scene(cfg, seed);
  const CosimResult calm = run_cosim(scene, ArchParams::resolve(cfg));
  expect_clean(calm);
  EXPECT_GT(calm.commands_2d, 0u);
  CosimOptions o = expect_stress_keeps(scene, cfg, calm, seed);
  // Valid gaps alone: assembly's withheld offers are stalled cycles, and the 2D engine
  // waits for its withheld operations while it holds the framebuffer port (busy).
  o.backpressure = 0;
  const CosimResult gaps = run_cosim(scene, ArchParams::resolve(cfg), o);
  expect_clean(gaps);
  EXPECT_EQ(gaps.crc_rtl, calm.crc_rtl);
  const auto stage = [](const CosimResult& c, StageId id) { return c.stages.at(stage_index(id)); };
  EXPECT_GT(stage(gaps, StageId::PrimAssembly).stalled, stage(calm, StageId::PrimAssembly).stalled);
  EXPECT_GT(stage(gaps, StageId::Engine2d).busy, stage(calm, StageId::Engine2d).busy);
  // The seed replays the run, cycle for cycle.
  EXPECT_EQ(run_cosim(scene, ArchParams::resolve(cfg), o).cycles_rtl, gaps.cycles_rtl);
}

// The same mixed scene with the config's DRAM model: the 2D engine's memory port waits for
// its operations' fills (rtl/rast_engine2d.sv, "Memory port"), and under backpressure on
// both memory ports, delayed 2D read responses and valid gaps every fragment, 2D pixel and
// the image are those of the calm run, which are the fixed run's (the memory system never
// changes a pixel), and the stalls cost cycles.
TEST(StressCosim, DramStressKeepsTheTwoDEngineExact) {
  Config cfg = load_shipped_config("default");
  cfg.apply_override("raster.out_of_range=cull");
  const Scene scene = mixed_scene(cfg, 0x57e55000u);
  Config fixed_cfg = cfg;
  fixed_cfg.apply_override("memory.model=fixed");
  const CosimResult fixed = run_cosim(scene, ArchParams::resolve(fixed_cfg));
  const CosimResult calm = run_cosim(scene, ArchParams::resolve(cfg));
  expect_clean(calm);
  EXPECT_GT(calm.commands_2d, 0u);
  EXPECT_EQ(calm.crc_rtl, fixed.crc_rtl);
  EXPECT_GT(calm.cycles_rtl, fixed.cycles_rtl) << "the fills cost cycles";
  expect_stress_keeps(scene, cfg, calm, 0x57e55001u);
}

// `n` random clip-space triangles in a 64 x 64 viewport, one tri4 a line: w in [0.05, 8]
// (1/w spread over up to 2^8), x and y within +-1.5 w (the view volume's edges cross
// them), z in [-0.2 w, 1.1 w] (near- and far-plane crossings), random colours, s and t
// in [-100, 100] repeats (most of s7.20's range), some triangles with flat s, t.
std::string random_clip_trace(uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::ostringstream os;
  os << "viewport 64 64\nclear 0 0 0\ncleardepth 1\n";
  for (int k = 0; k < n; ++k) {
    const bool flat_tex = k % 5 == 0;
    const float s0 = u(rng) * 200 - 100, t0 = u(rng) * 200 - 100;
    os << "tri4";
    for (int v = 0; v < 3; ++v) {
      const float w = 0.05f + 8.0f * u(rng) * u(rng);
      os << ' ' << (u(rng) * 3 - 1.5f) * w << ' ' << (u(rng) * 3 - 1.5f) * w << ' ' << (u(rng) * 1.3f - 0.2f) * w
         << ' ' << w << ' ' << rng() % 256 << ' ' << rng() % 256 << ' ' << rng() % 256 << ' '
         << (flat_tex ? s0 : u(rng) * 200 - 100) << ' ' << (flat_tex ? t0 : u(rng) * 200 - 100);
    }
    os << '\n';
  }
  return os.str();
}

struct ClipCase {
  const char* config;
  int samples;
};
class ClipSpaceCosim : public ::testing::TestWithParam<ClipCase> {};

TEST_P(ClipSpaceCosim, RandomPerspectiveTrianglesMatch) {
  Config cfg = load_shipped_config_fixed_memory(GetParam().config);
  cfg.apply_override("raster.samples=" + std::to_string(GetParam().samples));
  const uint64_t seed = 0xc11b0000u + uint64_t(GetParam().samples);
  std::cout << "seed " << seed << "\n";
  const Scene scene = parse_trace(random_clip_trace(seed, 120), "random_clip");
  CosimOptions o;
  o.backpressure = 0.3;
  o.valid_gaps = 0.3;
  o.stress_seed = seed;
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg), o);
  std::cout << r.fragments_compared << " fragments, " << r.triangles << " triangles, " << r.cycles_rtl << " cycles\n";
  expect_clean(r);
  EXPECT_EQ(r.crc_rtl, r.crc_ref);
  EXPECT_GT(r.fragments_compared, 2000u);
}

INSTANTIATE_TEST_SUITE_P(Configs, ClipSpaceCosim,
                         ::testing::Values(ClipCase{"default", 1}, ClipCase{"default", 4}, ClipCase{"d3d11", 1},
                                           ClipCase{"embedded", 1}, ClipCase{"desktop", 1}),
                         [](const auto& info) {
                           return std::string(info.param.config) + "Samples" + std::to_string(info.param.samples);
                         });

TEST(ClipSpaceCosimRefusal, ExactReciprocalWithAPerspectiveTriangleNamesTheLine) {
  Config cfg = load_shipped_config("default");
  cfg.apply_override("interp.recip=exact");
  const Scene scene = parse_trace("viewport 64 64\ntri4 -1 -1 0.5 1  1 -1 0.5 2  0 1 0.5 4\n", "persp");
  try {
    run_cosim(scene, ArchParams::resolve(cfg));
    ADD_FAILURE() << "interp.recip = exact with a perspective-correct triangle was co-simulated";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("persp:2: a perspective-correct triangle needs the reciprocal unit"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("interp.recip = \"newton\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim::rtlsim
