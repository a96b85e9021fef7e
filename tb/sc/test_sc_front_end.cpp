// SPDX-License-Identifier: Apache-2.0
// The geometry front end as a timed SystemC stage (sc/front_end.h, docs/clip-space.md
// "Levels"):
//
// - its cycles on a two-triangle clip-space scene equal the cost equation worked by hand
//   (TimingParams::front_end_step_cycles, docs/microarchitecture.md), and its counters
//   appear under stages.front_end;
// - screen-space scenes bypass it: every shipped screen-space trace keeps the image CRC
//   and cycle count it had before the stage existed, without and with random stalls
//   (each stage's stall generator keeps its seed: StageInfo::stall_stream).
#include <gtest/gtest.h>

#include <string>

#include "scene/scene_io.h"
#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

// Triangle A lies inside the view volume; triangle B's third vertex is behind the near
// plane (z = -0.5 < 0, w = 1 > 0), so the near plane cuts its two edges to that vertex:
// two new vertices, a quad, two triangles out. Every x and y is within +-w (no x/y plane).
constexpr const char* kTwoClipTriangles =
    "tri4 -0.5 -0.5 0.5 1  0.5 -0.5 0.5 1  0 0.5 0.5 1\n"
    "tri4 -0.5 -0.5 0.5 1  0.5 -0.5 0.5 1  0 0.5 -0.5 1\n";

TEST(ScFrontEnd, CyclesAreTheHandWorkedEquation) {
  const Config cfg = make_config({"display.width=32", "display.height=32", "front_end.cycles_per_primitive=3",
                                  "front_end.clip_cycles_per_vertex=5", "front_end.vertices_per_cycle=2",
                                  "front_end.latency_cycles=7", "fetch.cycles_per_command=1",
                                  "fetch.vertices_per_cycle=3", "assembly.cycles_per_triangle=1"});
  const Scene scene = parse_trace(kTwoClipTriangles, "two_clip.trace");
  const nlohmann::json j = run_isolated([&] { return simulate_stats(scene, cfg); });
  ASSERT_FALSE(j.contains("error")) << j["error"];
  const nlohmann::json& fe = j["stages"]["front_end"];
  // A: one primitive (3), no new vertex, its triangle's 3 vertices on 2 lanes (2): 5.
  // B: one primitive (3), two new vertices (2 x 5), the first triangle's 3 vertices (2):
  //    15; the second triangle's 1 new vertex (1): 1. Ends of commands: 0. Total 21.
  EXPECT_EQ(fe["busy"].get<uint64_t>(), 5u + 15u + 1u);
  EXPECT_EQ(fe["transactions_in"].get<uint64_t>(), 2u);   // two commands
  EXPECT_EQ(fe["transactions_out"].get<uint64_t>(), 5u);  // three triangles, two ends
  EXPECT_EQ(fe["clip_triangles_in"].get<uint64_t>(), 2u);
  EXPECT_EQ(fe["triangles_clipped"].get<uint64_t>(), 1u);
  EXPECT_EQ(fe["clip_vertices_made"].get<uint64_t>(), 2u);
  EXPECT_EQ(fe["clip_triangles_out"].get<uint64_t>(), 3u);
  // Fetch: a header and ceil(3 / 3) for each command, whole; assembly: 1 a triangle.
  EXPECT_EQ(j["stages"]["command_fetch"]["busy"].get<uint64_t>(), 2u * (1u + 1u));
  EXPECT_EQ(j["stages"]["prim_assembly"]["busy"].get<uint64_t>(), 3u);
  EXPECT_EQ(j["fifos"]["screen_fifo"]["depth"].get<int>(), 4 + 7);  // fifo.screen_depth + latency slots
  // The first triangle leaves the front end at fetch's 2 + 5 cycles and is ready 7 later:
  // assembly, setup, ... cannot finish before that.
  EXPECT_GE(j["cycles"].get<uint64_t>(), 2u + 5u + 7u);
}

// Every FIFO one entry deep, no pipeline slots, and random stalls: the front end's side
// path and the markers it joins never deadlock, lose or reorder a transaction, and the
// image and fragments are render's (the cube seen through the near plane: clipped,
// culled and fanned triangles).
TEST(ScFrontEnd, ClipCubeWithOneEntryFifosAndStallsMatchesReference) {
  const Config cfg = make_config({"fifo.command_depth=1", "fifo.triangle_depth=1", "fifo.setup_depth=1",
                                  "fifo.tile_depth=1", "fifo.pixel_depth=1", "fifo.fragment_depth=1",
                                  "fifo.clip_command_depth=1", "fifo.screen_depth=1", "front_end.latency_cycles=0",
                                  "setup.latency_cycles=2", "interp.latency_cycles=0"});
  const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/traces/3d/clip_cube.trace");
  sc::SimOptions stalls;
  stalls.stall_seed = 3;
  stalls.stall_probability = 0.3;
  const nlohmann::json r = run_isolated([&] { return compare_with_reference(scene, cfg, stalls); });
  expect_matches_reference(r);
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_GT(r["stats"]["stages"]["front_end"]["busy"].get<uint64_t>(), 0u);
  EXPECT_GT(r["stats"]["stages"]["front_end"]["triangles_clipped"].get<uint64_t>(), 0u);
}

// The figures of the model before the front end was a stage of its own (rastsim
// simulate on configs/default.toml; with stalls: --stall-probability 0.3 --seed 7), and
// before the reciprocal unit entered the interpolator's pipeline: the runs below set
// interp.perspective = false, which leaves it out (its 6 cycles of latency are
// TimingParams::interp_recip_latency's, tested in tb/sc/test_sc_timing.cpp).
struct ScreenSpaceRun {
  const char* trace;
  bool stalls;
  const char* crc;
  uint64_t cycles;
};
constexpr ScreenSpaceRun kBefore[] = {
    {"traces/2d/test_card.trace", false, "242a2d5c", 2811}, {"traces/2d/test_card.trace", true, "242a2d5c", 2871},
    {"traces/fill_rule.trace", false, "d2b8eff1", 1828},    {"traces/fill_rule.trace", true, "d2b8eff1", 1840},
    {"traces/primitives.trace", false, "42bed1a5", 1792},   {"traces/primitives.trace", true, "42bed1a5", 1804},
    {"traces/state.trace", false, "db225d0d", 2889},        {"traces/state.trace", true, "db225d0d", 2901},
    {"traces/torus.trace", false, "1708396b", 5915},        {"traces/torus.trace", true, "1708396b", 8095},
};

TEST(ScFrontEnd, ScreenSpaceScenesKeepTheirCyclesAndImage) {
  const Config cfg = make_config({"interp.perspective=false"});
  for (const ScreenSpaceRun& run : kBefore) {
    SCOPED_TRACE(std::string(run.trace) + (run.stalls ? " with stalls" : ""));
    const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/" + run.trace);
    sc::SimOptions opts;
    if (run.stalls) {
      opts.stall_seed = 7;
      opts.stall_probability = 0.3;
    }
    const nlohmann::json j = run_isolated([&] { return simulate_stats(scene, cfg, opts); });
    ASSERT_FALSE(j.contains("error")) << j["error"];
    EXPECT_EQ(j["framebuffer_crc32"].get<std::string>(), run.crc);
    EXPECT_EQ(j["cycles"].get<uint64_t>(), run.cycles);
    EXPECT_EQ(j["stages"]["front_end"]["busy"].get<uint64_t>(), 0u);  // bypassed
    EXPECT_EQ(j["stages"]["front_end"]["transactions_out"].get<uint64_t>(), 0u);
  }
}

}  // namespace
}  // namespace rastsim::sctest
