// SPDX-License-Identifier: Apache-2.0
// The decoupled model (stages run ahead of SystemC time, sc/stage.h) against the
// lock-step one (every stage waits for SystemC time to reach its own, as a clocked model
// does). In lock-step, each FIFO transfer is checked in the run against the SystemC time
// at which the blocked process resumes (Stage::check_lockstep: SystemC's scheduler, not
// the timestamps, decides that time), so a lock-step run that completes is the
// reference; the decoupled run must give every stat of it, cycle for cycle.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/random_2d_trace.h"
#include "sim_harness.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

// The stats of both runs, wall-time keys dropped.
void expect_lockstep_equal(const Scene& scene, const Config& cfg, sc::SimOptions o) {
  auto strip = [](nlohmann::json j) {
    for (const char* k : {"sim_wall_seconds", "wall_seconds", "simulated_cycles_per_second"}) j.erase(k);
    return j;
  };
  o.lockstep = false;
  const auto decoupled = run_isolated([&] { return simulate_stats(scene, cfg, o); });
  o.lockstep = true;
  const auto lockstep = run_isolated([&] { return simulate_stats(scene, cfg, o); });
  ASSERT_FALSE(decoupled.contains("error")) << decoupled["error"];
  ASSERT_FALSE(lockstep.contains("error")) << lockstep["error"];
  EXPECT_GT(lockstep["cycles"].get<uint64_t>(), 0u);
  EXPECT_EQ(strip(decoupled), strip(lockstep));
}

// Configs that stress the FIFOs and each stage differently: the defaults, every FIFO one
// deep, multisampling, the scanline walker, hierarchical tiles.
const std::vector<std::vector<std::string>> kConfigs = {
    {"raster.depth_func=less"},
    {"fifo.command_depth=1", "fifo.triangle_depth=1", "fifo.setup_depth=1", "fifo.tile_depth=1",
     "fifo.pixel_depth=1", "fifo.fragment_depth=1", "fifo.draw2d_depth=1", "fifo.op2d_depth=1",
     "raster.tile_size=8", "setup.latency_cycles=2", "interp.latency_cycles=0"},
    {"raster.samples=4", "raster.aa_mode=msaa", "raster.depth_func=less"},
    {"raster.traversal=scanline", "raster.scanline_arith=f64", "fifo.pixel_depth=1"},
    {"raster.traversal=hierarchical", "raster.hier_levels=32/8/2", "fifo.tile_depth=1"},
};

TEST(ScLockstep, DecoupledEqualsLockstepOnRandomScenes) {
  for (size_t c = 0; c < kConfigs.size(); ++c) {
    for (uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE("config " + std::to_string(c) + " seed " + std::to_string(seed));
      const Config cfg = make_config(kConfigs[c]);
      sc::SimOptions o;
      if (seed == 2) {  // injected stalls: the writers' extra cycles must agree too
        o.stall_seed = 7 + c;
        o.stall_probability = 0.3;
      }
      expect_lockstep_equal(random_scene(seed * 17 + c, 128, 96, 60), cfg, o);
    }
  }
}

TEST(ScLockstep, DecoupledEqualsLockstepOn2dScenes) {
  // The 2D path: the ROP lends its port to the 2D engine (two more Links, one deep).
  for (uint64_t seed : {3u, 4u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = parse_trace(testing::random_2d_trace(seed, 96, 80, 60), "random_2d");
    std::vector<std::string> sets{"display.width=96", "display.height=80"};
    if (seed == 4) sets.insert(sets.end(), {"fifo.draw2d_depth=1", "fifo.op2d_depth=1", "fifo.command_depth=1"});
    sc::SimOptions o;
    o.stall_seed = seed;
    o.stall_probability = seed == 4 ? 0.3 : 0;
    expect_lockstep_equal(scene, make_config(sets), o);
  }
}

TEST(ScLockstep, DecoupledEqualsLockstepOnClipSpace) {
  // The geometry front end's side path (two more Links) and the markers assembly waits
  // on: the clipped cube, then one-entry FIFOs with stalls.
  const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/traces/3d/clip_cube.trace");
  expect_lockstep_equal(scene, make_config({}), {});
  sc::SimOptions o;
  o.stall_seed = 9;
  o.stall_probability = 0.3;
  expect_lockstep_equal(scene,
                        make_config({"fifo.command_depth=1", "fifo.clip_command_depth=1", "fifo.screen_depth=1",
                                     "fifo.triangle_depth=1", "front_end.latency_cycles=0"}),
                        o);
}

// Textured scenes with memory.model = dram: the ROP and the texture stage, in two
// processes, share the DRAM, their requests in time order (SimContext::memory_time_order).
// On main the decoupled run gave 23,117 cycles and the lock-step one 24,260 on
// textured_cosim (it fails there): the ROP made a clear's writes after its busy (in
// lock-step, after SystemC time had passed their cycle), and a writer woken only once its
// FIFO was empty (sc/link.h) made its requests late in the decoupled run.
TEST(ScLockstep, DecoupledEqualsLockstepOnTexturedDram) {
  const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/tb/data/textured_cosim.trace");
  expect_lockstep_equal(scene, make_config({"memory.model=dram"}), {});
}

// The ROP and the texture stage make requests of the same cycle (on main the lock-step
// run put the texture's first, the decoupled one the ROP's: 28,731 against 29,847 cycles):
// at equal cycles the ROP's go first in both (sc/raster_pipeline.cpp, the arrival wait).
TEST(ScLockstep, DecoupledEqualsLockstepOnMipmappedDram) {
  const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/tb/data/textured_mip_cosim.trace");
  expect_lockstep_equal(scene, make_config({"memory.model=dram"}), {});
}

// A shipped config (configs/<name>.toml) with overrides, and a scene of the source tree.
Config config_file(const std::string& name, const std::vector<std::string>& overrides) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + name + ".toml");
  for (const auto& o : overrides) cfg.apply_override(o);
  cfg.validate();
  return cfg;
}
Scene source_scene(const std::string& rel) { return load_trace(std::string(RASTSIM_SOURCE_DIR) + "/" + rel); }

// Binned mode (pipeline.mode = binned), tb/cosim's cases: the binner and the ROP make
// DRAM requests in two processes, in time order. On main the default config's
// overflowing torus (4 KiB parameter buffer, 32 x 32 bins) gave 53,043 cycles decoupled
// against 54,159 in lock-step (a writer woken only once its FIFO was empty made its next
// requests late), and d3d11's torus in 16 x 16 bins equal cycles but other DRAM stats (a
// binner's and a ROP's request of one cycle entered in SystemC's process order).
TEST(ScLockstep, DecoupledEqualsLockstepBinned) {
  const Scene torus = source_scene("traces/torus.trace");
  const std::vector<std::string> binned{"pipeline.mode=binned", "raster.depth_func=less"};
  auto with = [&](std::vector<std::string> v) {
    v.insert(v.begin(), binned.begin(), binned.end());
    return v;
  };
  expect_lockstep_equal(
      torus, config_file("default", with({"bin.width=32", "bin.height=32", "bin.parameter_buffer_bytes=4096"})), {});
  expect_lockstep_equal(torus, config_file("d3d11", with({"bin.width=16", "bin.height=16"})), {});
  expect_lockstep_equal(torus, config_file("d3d11", with({"bin.width=16", "bin.height=16", "memory.model=fixed"})), {});
}

// Hi-Z (depth.hiz) and early Z (depth.early) on tb/cosim's scenes and the default config
// (memory.model = dram). On main: every Hi-Z run with a depth clear failed in lock-step
// (the ROP recorded the clear's interlock end after its busy: "write on tile_fifo timed at
// cycle 31 but SystemC is at cycle 285"); the spilled table (depth.hiz_bytes = 2048)
// differed (max layers 42,122 against 42,460, minmax torus 87,643 against 87,737) or
// failed in lock-step (the flush engine ended after the stages: max random "the stages end
// at cycle 97209 but SystemC at cycle 97360"); lagged with spilled blocks 40,705 against
// 48,318 on the layers (a decoupled test waited for an end past its cycle, its spilled
// reads then entered late); early Z on the torus with fixed memory 19,416 against 19,413
// (an interlock end at the batch's cycle counted or not as the ROP had recorded it).
TEST(ScLockstep, DecoupledEqualsLockstepHizAndEarlyZ) {
  const Scene layers = source_scene("tb/data/hiz_layers.trace");
  const Scene torus = source_scene("traces/torus.trace");
  const Scene random = source_scene("tb/data/hiz_random_seed7.trace.gz");
  struct Case {
    const Scene& scene;
    std::vector<std::string> sets;
  };
  const std::vector<Case> cases = {
      {layers, {"depth.hiz=max", "raster.depth_func=less"}},
      {torus, {"depth.hiz=max", "depth.hiz_sync=lagged", "raster.depth_func=less"}},
      {layers, {"depth.hiz=max", "depth.hiz_bytes=2048", "raster.depth_func=less"}},
      {torus, {"depth.hiz=minmax", "depth.hiz_bytes=2048", "raster.depth_func=less"}},
      {random, {"depth.hiz=max", "depth.hiz_bytes=2048", "raster.depth_func=lequal"}},
      {layers, {"depth.hiz=max", "depth.hiz_bytes=2048", "depth.hiz_sync=lagged", "raster.depth_func=less"}},
      {torus, {"depth.hiz=minmax", "depth.hiz_bytes=2048", "depth.hiz_sync=lagged", "raster.depth_func=less"}},
      {torus, {"depth.early=true", "raster.depth_func=less", "memory.model=fixed"}},
  };
  for (const Case& c : cases) {
    std::string name;
    for (const auto& k : c.sets) name += k + " ";
    SCOPED_TRACE(name);
    expect_lockstep_equal(c.scene, config_file("default", c.sets), {});
  }
}

}  // namespace
}  // namespace rastsim::sctest
