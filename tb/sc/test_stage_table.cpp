// SPDX-License-Identifier: Apache-2.0
// The stage and FIFO table (model/timing/stage_table.h) is the one list: the SystemC
// model's stages and FIFOs, the analytic estimate's stages and the sampled level's FIFO
// capacity all follow it, and the fill latencies it derives equal the hand-worked sums of
// docs/microarchitecture.md. (The RTL testbench's stage list: tb/cosim/test_stages.cpp.)
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "estimate/estimate.h"
#include "fidelity/sampled.h"
#include "ref/scene.h"
#include "sc/sim_harness.h"
#include "scene/scene_io.h"
#include "timing/stage_table.h"

namespace rastsim {
namespace {

Config test_config() {
  Config cfg;
  cfg.apply_override("display.width=64");
  cfg.apply_override("display.height=64");
  cfg.apply_override("setup.latency_cycles=9");  // pipeline latencies that show in the fill
  cfg.apply_override("setup.interval_cycles=3");
  cfg.validate();
  return cfg;
}

Scene one_triangle() {
  return parse_trace("tri 2 2 40 4 10 50\n", "one.trace");
}

// The fills, worked by hand from the cost terms (docs/microarchitecture.md): fetch's
// header, then one issue cycle a stage, plus setup's pipeline (latency - interval) behind
// setup and the interpolation latency behind interpolation; the 2D stages and the
// geometry front end wait for the header alone.
TEST(StageTable, FillCyclesAreTheHandWorkedSums) {
  const TimingParams t = ArchParams::resolve(test_config()).timing;
  // Interpolation's latency: the dividers' and (interp.perspective on) the reciprocal
  // unit's, 1 + 2 steps + 1 stages.
  ASSERT_TRUE(t.interp_perspective);
  const uint64_t f = t.fetch_cycles_per_command, setup = t.setup_latency - t.setup_interval,
                 il = t.interp_latency + 2 + 2 * t.recip_iterations;
  ASSERT_GT(setup, 0u);
  EXPECT_EQ(t.stage_fill_cycles(StageId::CommandFetch), 0u);
  EXPECT_EQ(t.stage_fill_cycles(StageId::FrontEnd), f);      // beside the triangle path
  EXPECT_EQ(t.stage_fill_cycles(StageId::PrimAssembly), f);  // the front end not counted: bypassed
  EXPECT_EQ(t.stage_fill_cycles(StageId::TriSetup), f + 1);
  EXPECT_EQ(t.stage_fill_cycles(StageId::CoarseRaster), f + 2 + setup);
  EXPECT_EQ(t.stage_fill_cycles(StageId::FineRaster), f + 3 + setup);
  EXPECT_EQ(t.stage_fill_cycles(StageId::Interpolate), f + 4 + setup);
  EXPECT_EQ(t.stage_fill_cycles(StageId::Rop), f + 5 + setup + il);
  EXPECT_EQ(t.stage_fill_cycles(StageId::Draw2dSetup), f);
  EXPECT_EQ(t.stage_fill_cycles(StageId::Engine2d), f);
  EXPECT_EQ(sc::fixed_latency_cycles(t), f + 6 + setup + il);
}

TEST(StageTable, SystemCStagesAndFifosFollowTheTable) {
  const nlohmann::json j = sctest::simulate_stats(one_triangle(), test_config());
  ASSERT_FALSE(j.contains("error")) << j["error"];
  const TimingParams t = ArchParams::resolve(test_config()).timing;
  ASSERT_EQ(j["stages"].size(), kStageCount);
  for (const StageInfo& s : kStages) EXPECT_TRUE(j["stages"].contains(std::string(s.name))) << s.name;
  ASSERT_EQ(j["fifos"].size(), kFifoCount);
  for (const FifoInfo& f : kFifos) {
    SCOPED_TRACE(std::string(f.name));
    ASSERT_TRUE(j["fifos"].contains(std::string(f.name)));
    EXPECT_EQ(j["fifos"][std::string(f.name)]["depth"].get<int>(), t.fifo_entries(f.id));
  }
}

TEST(StageTable, EstimateStagesFollowTheTable) {
  const EstimateResult r = estimate_scene(one_triangle(), ArchParams::resolve(test_config()));
  const nlohmann::json j = r.to_json();
  ASSERT_EQ(j["stages"].size(), kStageCount);
  for (const StageInfo& s : kStages) EXPECT_TRUE(j["stages"].contains(std::string(s.name))) << s.name;
  EXPECT_GT(r.stages[stage_index(StageId::Rop)].busy, 0u);
  EXPECT_EQ(r.stages[stage_index(StageId::Engine2d)].busy, 0u);
}

// The sampled level's run-ahead capacity is every triangle-path FIFO's entries: the six
// between command fetch and the ROP, counted here by hand, and not the 2D path's.
TEST(StageTable, SampledCapacityIsTheTrianglePathFifos) {
  const TimingParams t = ArchParams::resolve(test_config()).timing;
  const uint64_t by_hand = uint64_t(t.fifo_command + t.fifo_triangle + t.setup_fifo_entries() + t.fifo_tile +
                                    t.fifo_pixel + t.fragment_fifo_entries());
  EXPECT_EQ(fidelity::triangle_path_entries(t), by_hand);
  std::set<std::string> on_path;
  for (const FifoInfo& f : kFifos)
    if (on_triangle_path(f)) on_path.insert(std::string(f.name));
  EXPECT_EQ(on_path, (std::set<std::string>{"command_fifo", "triangle_fifo", "setup_fifo", "tile_fifo", "pixel_fifo",
                                            "fragment_fifo"}));
}

}  // namespace
}  // namespace rastsim
