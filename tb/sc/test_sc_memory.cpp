// SPDX-License-Identifier: Apache-2.0
// The timed memory system (model/timing/memory_system.h; docs/memory.md, "Timed memory system
// (SystemC)"):
//
// - with memory.model = dram, simulate's image, every render counter and every cache,
//   byte and fast-clear count equal render's with the same memory settings, on every
//   shipped trace (the 2D test card too: the 2D engine draws through the ROP's colour
//   client) and several settings (the functional model is the reference's, fed the
//   ROP's and the 2D engine's stream in pipeline order);
// - a scene whose line fills dominate costs more cycles with DRAM than with the fixed
//   costs (each transaction with a fill lasts at least its fixed cycles and at least
//   the unloaded row-miss latency), and the DRAM's data bus is never busier than the
//   run's time allows (utilisation <= 1);
// - memory.model = fixed reports none of the memory system's keys;
// - --mem-trace lists every burst: replayed through the DRAM model as `rastsim
//   dram-replay` does, it moves the same bytes.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <fstream>

#include "config/arch_params.h"
#include "report/stats_json.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"
#include "sim_harness.h"
#include "timing/dram_trace.h"

namespace rastsim::sctest {
namespace {

TEST(ScMemory, CountsEqualRenderOnTraces) {
  const std::vector<std::vector<std::string>> settings = {
      {},
      {"rop.fast_clear=true", "rop.depth_compression=plane", "memory.fb_layout=tiled"},
  };
  for (const std::string& path : shipped_traces()) {
    for (const auto& extra : settings) {
      SCOPED_TRACE(path + (extra.empty() ? " defaults" : " fast clear, plane, tiled"));
      std::vector<std::string> kv = {"memory.model=dram", "raster.depth_func=less"};
      kv.insert(kv.end(), extra.begin(), extra.end());
      const Scene scene = load_trace(path);
      const nlohmann::json r = run_isolated([&] { return render_and_simulate(scene, make_config(kv)); });
      ASSERT_FALSE(r.contains("error")) << r["error"];
      EXPECT_EQ(r["sim"], r["ref"]);
      ASSERT_TRUE(r["sim"].contains("dram_bytes_read"));
      const auto& s = r["stats"];
      EXPECT_LE(s["dram_bandwidth_utilisation"].get<double>(), 1.0);
      EXPECT_GE(s["dram_row_hit_rate"].get<double>(), 0.0);
      EXPECT_LE(s["dram_row_hit_rate"].get<double>(), 1.0);
    }
  }
}

TEST(ScMemory, MultisampleCountsEqualRender) {
  const Scene scene = random_scene(7, 64, 48, 30);
  const Config cfg = make_config({"memory.model=dram", "raster.samples=4", "display.width=64", "display.height=48",
                                  "raster.depth_func=less"});
  const nlohmann::json r = run_isolated([&] { return render_and_simulate(scene, cfg); });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["sim"], r["ref"]);
}

// A full-screen quad, depth test on: every fragment reads depth, so every 16th (a
// 64-byte line of 4-byte depths) misses and waits for DRAM.
Scene fill_bound_scene() {
  return parse_trace(
      "viewport 128 128\n"
      "clear 0 0 0\n"
      "tri 0 0 0.5 255 0 0  0 128 0.5 255 0 0  128 0 0.5 255 0 0\n"
      "tri 128 0 0.5 0 255 0  0 128 0.5 0 255 0  128 128 0.5 0 255 0\n",
      "quad");
}

TEST(ScMemory, FillsCostCyclesWithinTheBusBound) {
  const Scene scene = fill_bound_scene();
  const std::vector<std::string> common = {"raster.depth_func=less", "display.width=128", "display.height=128"};
  auto with = [&](const char* model) {
    std::vector<std::string> kv = common;
    kv.push_back(std::string("memory.model=") + model);
    return make_config(kv);
  };
  const nlohmann::json fixed = run_isolated([&] { return simulate_stats(scene, with("fixed")); });
  const nlohmann::json dram = run_isolated([&] { return simulate_stats(scene, with("dram")); });
  ASSERT_FALSE(fixed.contains("error")) << fixed["error"];
  ASSERT_FALSE(dram.contains("error")) << dram["error"];
  const uint64_t cf = fixed["cycles"], cd = dram["cycles"];
  // Each ROP transaction lasts at least its fixed cycles; the depth misses' fills
  // (128 x 128 / 16 = 1024 lines) each take at least one row access, tens of cycles.
  EXPECT_GT(cd, cf);
  EXPECT_EQ(dram["rop_depth_cache_misses"].get<uint64_t>(), 128u * 128u / 16u);
  // A zero-latency memory would leave the cycles at the fixed run's; the DRAM's busy
  // data bus fits in the run's time.
  const double util = dram["dram_bandwidth_utilisation"];
  EXPECT_GT(util, 0.0);
  EXPECT_LE(util, 1.0);
  EXPECT_GT(dram["memory"]["clients"]["rop_depth"]["mean_read_latency_cycles"].get<double>(), 1.0);
  EXPECT_FALSE(fixed.contains("dram_row_hit_rate"));
  EXPECT_FALSE(fixed.contains("memory"));
}

TEST(ScMemory, TraceReplaysToTheSameBytes) {
  const Scene scene = fill_bound_scene();
  const Config cfg = make_config({"raster.depth_func=less", "memory.model=dram"});
  const std::string path =
      (std::filesystem::temp_directory_path() / ("sc_mem_trace_" + std::to_string(::getpid()) + ".trace")).string();
  sc::SimOptions o;
  o.mem_trace_path = path;
  const nlohmann::json s = run_isolated([&] { return simulate_stats(scene, cfg, o); });
  ASSERT_FALSE(s.contains("error")) << s["error"];
  std::ifstream in(path);
  const std::vector<DramTraceLine> lines = read_dram_trace(in, path);
  std::filesystem::remove(path);
  // As dram-replay: every line one burst at its DRAM clock, on the same parameters.
  DramParams p = ArchParams::resolve(cfg).dram;
  p.core_khz = p.dram_khz;
  DramModel m(p);
  for (size_t i = 0; i < lines.size(); ++i) {
    for (uint64_t at = m.next_event(); at != DramModel::kNoEvent && at <= lines[i].clock; at = m.next_event()) {
      m.advance_to(at);
      m.take_completions();  // a completion not taken stays the next event
    }
    m.enqueue({lines[i].address, lines[i].write, uint32_t(p.burst_bytes()), 0, i}, lines[i].clock);
  }
  for (uint64_t at = m.next_event(); at != DramModel::kNoEvent; at = m.next_event()) {
    m.advance_to(at);
    m.take_completions();
  }
  const DramClientStats t = m.stats().total();
  EXPECT_GT(t.bytes_read, 0u);
  EXPECT_EQ(t.bytes_read, s["memory"]["dram"]["bytes_read"].get<uint64_t>());
  EXPECT_EQ(t.bytes_written, s["memory"]["dram"]["bytes_written"].get<uint64_t>());
}

}  // namespace
}  // namespace rastsim::sctest
