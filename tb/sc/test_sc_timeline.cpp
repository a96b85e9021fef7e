// SPDX-License-Identifier: Apache-2.0
// Where the cycles go: the --timeline trace and the --heatmap tile costs, checked
// against the stage counters they must agree with (the stats JSON's busy/stalled/
// starved, which every other timing test checks) and against a hand-placed triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numeric>

#include <unistd.h>

#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

std::string temp_path(const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/rastsim_timeline_" + std::to_string(getpid()) + "_" + name;
}

// In a child: the stats of one run that also wrote a timeline and filled the heat grids.
nlohmann::json run_recorded(const Scene& scene, const Config& cfg, const std::string& timeline, uint64_t max_events,
                            double stall_probability = 0) {
  return run_isolated([&] {
    sc::SimOptions o;
    o.timeline_path = timeline;
    o.timeline_max_events = max_events;
    o.heatmap = true;
    o.stall_seed = 7;
    o.stall_probability = stall_probability;
    const sc::SimResult r = sc::simulate_scene(scene, ArchParams::resolve(cfg), o);
    nlohmann::json j = r.to_json();
    j["timeline_events"] = r.timeline.events;
    j["timeline_resolution"] = r.timeline.resolution_cycles;
    for (const sc::TileHeat& h : r.heat)
      j["heat"][h.stage] = {{"tiles", h.cycles}, {"unattributed", h.unattributed}, {"tiles_x", h.tiles_x}};
    return j;
  });
}

// Checks a trace file against the run's stats: one track per stage and FIFO, every
// stage's intervals disjoint and summing to the run's cycles state by state, every FIFO
// within its depth. Returns the number of "X" and "C" events.
size_t check_trace(const std::string& path, const nlohmann::json& stats) {
  std::ifstream is(path);
  EXPECT_TRUE(is) << path;
  const nlohmann::json t = nlohmann::json::parse(is);  // throws (fails the test) if malformed
  const uint64_t cycles = stats["cycles"];
  std::map<int, std::string> stage_tid, fifo_tid;  // tid -> name
  std::map<std::string, std::vector<std::tuple<uint64_t, uint64_t, std::string>>> x;  // stage -> intervals
  std::map<std::string, std::vector<int>> c;                                           // fifo -> values
  size_t events = 0;
  for (const auto& e : t["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "thread_name")
      (e["pid"] == 1 ? stage_tid : fifo_tid)[e["tid"].get<int>()] = e["args"]["name"];
  for (const auto& e : t["traceEvents"]) {
    if (e["ph"] == "X") {
      ++events;
      EXPECT_EQ(e["pid"], 1);
      x[stage_tid.at(e["tid"].get<int>())].emplace_back(e["ts"], e["dur"], e["name"]);
    } else if (e["ph"] == "C") {
      ++events;
      c[e["name"]].push_back(e["args"]["occupancy"]);
    }
  }
  // One track per stage and per FIFO, named as in the stats.
  EXPECT_EQ(stage_tid.size(), stats["stages"].size());
  for (const auto& [tid, name] : stage_tid) EXPECT_TRUE(stats["stages"].contains(name)) << name;
  EXPECT_EQ(fifo_tid.size(), stats["fifos"].size());
  for (const auto& [name, fifo] : stats["fifos"].items()) {
    SCOPED_TRACE(name);
    const int depth = fifo["depth"];
    for (int v : c[name]) {
      EXPECT_GE(v, 0);
      EXPECT_LE(v, depth);
    }
    EXPECT_FALSE(c[name].empty()) << "every FIFO has a counter track, used or not";
  }
  for (const auto& [name, st] : stats["stages"].items()) {
    SCOPED_TRACE(name);
    auto& iv = x[name];
    std::map<std::string, uint64_t> sum;
    uint64_t end = 0;
    for (const auto& [ts, dur, state] : iv) {  // written in time order
      EXPECT_GE(ts, end) << "overlap at " << ts;
      EXPECT_GT(dur, 0u);
      end = ts + dur;
      sum[state] += dur;
    }
    EXPECT_EQ(sum["busy"] + sum["stalled"] + sum["starved"], cycles);
    EXPECT_EQ(sum["busy"], st["busy"].get<uint64_t>());
    EXPECT_EQ(sum["stalled"], st["stalled"].get<uint64_t>());
    EXPECT_EQ(sum["starved"], st["starved"].get<uint64_t>());
  }
  return events;
}

TEST(ScTimeline, TracksAgreeWithStageCounters) {
  const Scene scene = random_scene(31, 128, 96, 80);  // clears, scissor, viewport change
  const Config cfg = make_config({"display.width=128", "display.height=96"});
  for (double stalls : {0.0, 0.3}) {
    SCOPED_TRACE(stalls);
    const std::string path = temp_path("exact.json");
    const nlohmann::json s = run_recorded(scene, cfg, path, 1'000'000, stalls);
    ASSERT_FALSE(s.contains("error")) << s["error"];
    EXPECT_EQ(s["timeline_resolution"], 1);
    check_trace(path, s);
    std::remove(path.c_str());
  }
}

TEST(ScTimeline, QuantizedTraceKeepsExactSumsWithinBudget) {
  const Scene scene = random_scene(32, 128, 96, 300);
  const Config cfg = make_config({"display.width=128", "display.height=96"});
  const std::string path = temp_path("quantized.json");
  const uint64_t budget = 1000;
  const nlohmann::json s = run_recorded(scene, cfg, path, budget, 0.2);
  ASSERT_FALSE(s.contains("error")) << s["error"];
  EXPECT_GT(s["timeline_resolution"].get<uint64_t>(), 1u) << "the scene should need quantizing";
  EXPECT_LE(check_trace(path, s), budget);
  std::remove(path.c_str());
}

TEST(ScTimeline, RecordingDoesNotChangeTiming) {
  const Scene scene = random_scene(33, 128, 96, 60);
  const Config cfg = make_config({"display.width=128", "display.height=96"});
  const std::string path = temp_path("same.json");
  const nlohmann::json on = run_recorded(scene, cfg, path, 1'000'000);
  const nlohmann::json off = run_isolated([&] { return simulate_stats(scene, cfg); });
  ASSERT_FALSE(on.contains("error")) << on["error"];
  EXPECT_EQ(on["cycles"], off["cycles"]);
  EXPECT_EQ(on["stages"], off["stages"]);
  std::remove(path.c_str());
}

TEST(ScHeatmap, TilesSumToBusyCycles) {
  for (const char* method : {"tiled", "hierarchical", "bbox", "scanline"}) {
    SCOPED_TRACE(method);
    const Scene scene = random_scene(34, 128, 96, 80);
    const Config cfg = make_config({"display.width=128", "display.height=96", std::string("raster.traversal=") + method});
    const std::string path = temp_path("heat.json");
    const nlohmann::json s = run_recorded(scene, cfg, path, 1'000'000);
    ASSERT_FALSE(s.contains("error")) << s["error"];
    ASSERT_EQ(s["heat"].size(), 4u);
    for (const auto& [stage, h] : s["heat"].items()) {
      SCOPED_TRACE(stage);
      const auto tiles = h["tiles"].get<std::vector<uint64_t>>();
      const uint64_t sum = std::accumulate(tiles.begin(), tiles.end(), uint64_t{0});
      EXPECT_EQ(sum + h["unattributed"].get<uint64_t>(), s["stages"][stage]["busy"].get<uint64_t>());
      EXPECT_GT(sum, 0u);
    }
    std::remove(path.c_str());
  }
}

// A hand-placed triangle inside tile (2, 1) of 16 px tiles: all its work lands there;
// only the viewport command (1 cycle in each stage) is of no tile.
TEST(ScHeatmap, OneTriangleLandsInItsTile) {
  Scene scene;
  scene.commands.push_back({CmdViewport{128, 96}, {"mem", 1}});
  CmdPrimitives tri;
  tri.vertices.push_back({Q64::from_double(34), Q64::from_double(18), 0.5});
  tri.vertices.push_back({Q64::from_double(45), Q64::from_double(19), 0.5});
  tri.vertices.push_back({Q64::from_double(36), Q64::from_double(29), 0.5});
  scene.commands.push_back({tri, {"mem", 2}});
  const Config cfg = make_config({"display.width=128", "display.height=96", "raster.tile_size=16"});
  const std::string path = temp_path("one.json");
  const nlohmann::json s = run_recorded(scene, cfg, path, 1'000'000);
  ASSERT_FALSE(s.contains("error")) << s["error"];
  ASSERT_EQ(s["heat"].size(), 4u);
  for (const auto& [stage, h] : s["heat"].items()) {
    SCOPED_TRACE(stage);
    const auto tiles = h["tiles"].get<std::vector<uint64_t>>();
    const size_t at = 1 * size_t(h["tiles_x"].get<int>()) + 2;
    EXPECT_EQ(h["tiles_x"], 8);
    EXPECT_EQ(h["unattributed"], 1u);
    for (size_t i = 0; i < tiles.size(); ++i) {
      if (i != at) {
        EXPECT_EQ(tiles[i], 0u) << "tile " << i;
      }
    }
    EXPECT_EQ(tiles[at] + 1, s["stages"][stage]["busy"].get<uint64_t>());
  }
  check_trace(path, s);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rastsim::sctest
