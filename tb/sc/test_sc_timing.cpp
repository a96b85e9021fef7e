// SPDX-License-Identifier: Apache-2.0
// Timing sanity of the SystemC model: properties that hold for any correct pipelined
// implementation of the documented equations (docs/microarchitecture.md), each of which
// a timing bug can break.
#include <gtest/gtest.h>

#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

using sc::TimingParams;

uint64_t cycles_of(const nlohmann::json& s) {
  EXPECT_FALSE(s.contains("error")) << s["error"];
  return s.value("cycles", uint64_t{0});
}

TEST(ScTiming, EmptySceneCostsOnlyFixedLatency) {
  const Config cfg;
  const TimingParams p = TimingParams::from_config(cfg);
  // No commands: nothing happens.
  EXPECT_EQ(cycles_of(run_isolated([&] { return simulate_stats(Scene{}, cfg); })), 0u);
  // One state command: fetch header, one cycle in each later stage, and the setup and
  // interpolation pipeline latencies (fixed_latency_cycles).
  Scene viewport;
  viewport.commands.push_back({CmdViewport{100, 100}, {"mem", 1}});
  EXPECT_EQ(cycles_of(run_isolated([&] { return simulate_stats(viewport, cfg); })), sc::fixed_latency_cycles(p));
  // A triangle entirely outside the viewport costs fetch, assembly and setup only.
  Scene outside = viewport;
  CmdPrimitives tri;
  for (double x : {120.0, 140.0, 130.0}) tri.vertices.push_back({Q64::from_double(x), Q64::from_double(x - 110), 0.5});
  outside.commands.push_back({tri, {"mem", 2}});
  const uint64_t c = cycles_of(run_isolated([&] { return simulate_stats(outside, cfg); }));
  EXPECT_LE(c, sc::fixed_latency_cycles(p) + p.fetch_cycles_per_command + 3 + p.assembly_cycles_per_triangle +
                   p.setup_interval);
}

TEST(ScTiming, DisjointCopiesCostAboutNTimesOne) {
  const Config cfg = make_config({"raster.tile_size=16"});
  const Scene one = random_scene(21, 128, 128, 40);
  const uint64_t c1 = cycles_of(run_isolated([&] { return simulate_stats(one, cfg); }));
  for (int n : {2, 5}) {
    SCOPED_TRACE(n);
    const Scene many = repeat_scene(one, n);
    const uint64_t cn = cycles_of(run_isolated([&] { return simulate_stats(many, cfg); }));
    // Copies overlap only in fill and drain: between 90 % and 100 % of N x one.
    EXPECT_LE(cn, n * c1);
    EXPECT_GE(double(cn), 0.9 * n * double(c1));
  }
}

TEST(ScTiming, DoublingFineSamplesNeverIncreasesCycles) {
  const Scene scene = random_scene(22, 128, 128, 60);
  for (int tile : {8, 32}) {
    uint64_t previous = UINT64_MAX;
    for (int spc = 1; spc <= 64; spc *= 2) {
      SCOPED_TRACE("tile " + std::to_string(tile) + " samples/cycle " + std::to_string(spc));
      const Config cfg =
          make_config({"raster.tile_size=" + std::to_string(tile), "fine.samples_per_cycle=" + std::to_string(spc)});
      const uint64_t c = cycles_of(run_isolated([&] { return simulate_stats(scene, cfg); }));
      EXPECT_LE(c, previous);
      previous = c;
    }
  }
}

TEST(ScTiming, BottleneckStageSetsThroughput) {
  // A slow ROP dominates: cycles are within 10 % of its busy time, and above the bound.
  const Config cfg = make_config({"rop.pixels_per_cycle=1", "fine.samples_per_cycle=64",
                                  "interp.fragments_per_cycle=64"});
  const Scene scene = random_scene(23, 128, 128, 40);
  const auto s = run_isolated([&] { return simulate_stats(scene, cfg); });
  const uint64_t c = cycles_of(s);
  const uint64_t rop_busy = s["stages"]["rop"]["busy"];
  EXPECT_GE(c, s["cycles_lower_bound"].get<uint64_t>());
  EXPECT_LE(double(c), 1.1 * double(rop_busy));
  // The ROP's fill: fetch, 5 stages, and the setup and interpolation pipeline latencies
  // (interp.perspective is on: the reciprocal unit's 1 + 2 steps + 1 stages too).
  const TimingParams p = TimingParams::from_config(cfg);
  ASSERT_TRUE(p.interp_perspective);
  const uint64_t rop_fill = p.fetch_cycles_per_command + 5 + (p.setup_latency - p.setup_interval) + p.interp_latency +
                            2 + 2 * p.recip_iterations;
  EXPECT_EQ(rop_busy, s["cycles_lower_bound"].get<uint64_t>() - rop_fill);
}

TEST(ScTiming, SetupLatencyIsNotThroughput) {
  // Triangles that each cover little: setup dominates. Its interval sets throughput;
  // a longer latency with the same interval adds only about one latency in total.
  Scene scene = random_scene(24, 128, 128, 1);
  scene.commands.resize(3);  // viewport, clear, clear depth
  for (int i = 0; i < 300; ++i) {
    CmdPrimitives p;
    const double x = 1 + (i % 100), y = 1 + (i / 100) * 30;
    p.vertices = {{Q64::from_double(x), Q64::from_double(y), 0.5},
                  {Q64::from_double(x + 0.9), Q64::from_double(y), 0.5},
                  {Q64::from_double(x), Q64::from_double(y + 0.9), 0.5}};
    scene.commands.push_back({p, {"mem", i + 4}});
  }
  auto run = [&](int interval, int latency) {
    const Config cfg = make_config({"setup.interval_cycles=" + std::to_string(interval),
                                    "setup.latency_cycles=" + std::to_string(latency)});
    return cycles_of(run_isolated([&] { return simulate_stats(scene, cfg); }));
  };
  const uint64_t base = run(4, 4), deep = run(4, 40), slow = run(8, 8);
  EXPECT_NEAR(double(deep), double(base + 36), 4.0);
  EXPECT_GE(double(slow), 1.8 * double(base) - 100);
}

}  // namespace
}  // namespace rastsim::sctest
