// SPDX-License-Identifier: Apache-2.0
// Failures inside the timed model keep their type: bad input stays a SceneError, a fault
// of the model (a Link ordering failure) is a ModelError and never a SceneError.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "sim_harness.h"
#include "sc/model_error.h"
#include "sc/raster_pipeline.h"
#include "sc/stage.h"

namespace rastsim::sctest {
namespace {

// "scene", "model" or "other": the type of what `fn` threw ("none" if nothing).
template <class F>
std::string thrown_kind(F&& fn) {
  try {
    fn();
  } catch (const SceneError&) {
    return "scene";
  } catch (const sc::ModelError&) {
    return "model";
  } catch (...) {
    return "other";
  }
  return "none";
}

TEST(ScErrors, LinkOrderCheckThrowsModelError) {
  EXPECT_EQ(thrown_kind([] { sc::check_order("pipeline.tile_fifo", 3, 4); }), "model");
  EXPECT_EQ(thrown_kind([] { sc::check_order("pipeline.tile_fifo", 3, 3); }), "none");
  try {
    sc::check_order("pipeline.tile_fifo", 0, 2);
  } catch (const sc::ModelError& e) {
    EXPECT_STREQ(e.what(), "pipeline.tile_fifo: expected transaction #0, got #2 (lost or reordered)");
  }
}

// A one-stage design whose body raises `fault` at cycle 3, as a failing stage would.
struct FaultyStage : sc::Stage {
  FaultyStage(sc_core::sc_module_name n, sc::SimContext& ctx, void (*fault)()) : Stage(n, ctx, StageId::CommandFetch), fault_(fault) {}
  void body() override {
    busy(3);
    fault_();
  }
  void (*fault_)();
};

// In a child: elaborates FaultyStage, runs it and reports the type rethrown after sc_start.
nlohmann::json rethrown_kind(void (*fault)()) {
  return run_isolated([fault] {
    sc::SimContext ctx;
    FaultyStage stage("stage", ctx, fault);
    sc_core::sc_start();
    return nlohmann::json{{"kind", thrown_kind([&] { ctx.rethrow_failure(); })}};
  });
}

TEST(ScErrors, LinkOrderFailureInAStageIsNotASceneError) {
  const auto r = rethrown_kind([] { sc::check_order("pipeline.setup_fifo", 1, 0); });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["kind"], "model");
}

TEST(ScErrors, SceneErrorInAStageStaysASceneError) {
  const auto r = rethrown_kind([] { throw SceneError("t.trace:3: bad vertex"); });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["kind"], "scene");
}

// The timed model has no geometry front end yet: a clip-space command is a scene error
// naming its line, not a command that draws nothing.
// The timed model runs the reference's front end: a clip-space value it cannot divide
// by (not finite) stops the simulation with the front end's SceneError, naming the line.
TEST(ScErrors, NonFiniteClipSpaceValueIsASceneError) {
  const auto r = run_isolated([] {
    Scene scene;
    CmdPrimitives p;
    p.clip_vertices.assign(3, ClipVertex{});
    p.clip_vertices[1].w = std::numeric_limits<float>::infinity();
    scene.commands.push_back(Command{p, SourceLoc{"c.trace", 4}});
    try {
      sc::simulate_scene(scene, ArchParams::resolve(Config{}));
    } catch (const SceneError& e) {
      return nlohmann::json{{"what", e.what()}};
    }
    return nlohmann::json{{"what", "no error"}};
  });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["what"].get<std::string>().rfind("c.trace:4: clip-space vertex 1 has a value that is not a finite", 0), 0u)
      << r["what"];
}

}  // namespace
}  // namespace rastsim::sctest
