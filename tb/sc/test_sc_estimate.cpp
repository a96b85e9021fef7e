// SPDX-License-Identifier: Apache-2.0
// The analytic level (model/estimate, docs/estimate.md) against the SystemC model:
//
// - every stage's busy total equals the SystemC stage's `busy` exactly (both sum the
//   same TimingParams cost functions over the same transactions), and so do the
//   transactions each stage writes;
// - the SystemC cycle count lies within [cycles_lower_bound, cycles_upper_bound] on
//   every shipped trace and config, on seeded random triangle scenes with and without
//   2D commands, with every raster.traversal and with one-entry FIFOs, and with 4 and 8
//   samples (msaa and ssaa) under every exact traversal;
// - with random stall injection the busy totals still agree and the lower bound holds
//   (the upper bound does not cover injected stalls, which are not work);
// - with memory.model = "dram": the bandwidth bound (bytes the ROP reads / the DRAM's
//   peak) holds on every shipped trace and config, binds on a hand-worked fill-bound
//   quad over a slowed DRAM, and there is no upper bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "common/random_2d_trace.h"
#include "estimate/estimate.h"
#include "sim_harness.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

// Simulates in a child, estimates here, and checks the contract; `upper_bound_holds` =
// false skips the upper bound (stall injection). Returns false when the scene is bad
// input for both levels (nothing compared), so callers can insist on real comparisons.
bool check_against_systemc(const Scene& scene, const Config& cfg, const sc::SimOptions& opts = {},
                           bool upper_bound_holds = true) {
  const nlohmann::json sim = run_isolated([&] { return simulate_stats(scene, cfg, opts); });
  if (sim.contains("error")) {
    // Bad input fails both levels alike.
    EXPECT_ANY_THROW(estimate_scene(scene, ArchParams::resolve(cfg))) << "SystemC failed with " << sim["error"];
    return false;
  }
  const EstimateResult est = estimate_scene(scene, ArchParams::resolve(cfg));
  const uint64_t cycles = sim["cycles"];
  EXPECT_LE(est.cycles_lower_bound, cycles);
  if (upper_bound_holds) {
    EXPECT_GE(est.cycles_upper_bound, cycles);
    EXPECT_LE(est.cycles_lower_bound, est.cycles_estimate);
    EXPECT_LE(est.cycles_estimate, est.cycles_upper_bound);
  }
  // SystemC's own lower bound is the same formula over the same busy totals.
  EXPECT_EQ(est.cycles_lower_bound, sim["cycles_lower_bound"].get<uint64_t>());
  for (size_t s = 0; s < kStageCount; ++s) {
    const std::string name(kStages[s].name);
    const nlohmann::json& st = sim["stages"][name];
    EXPECT_EQ(est.stages[s].busy, st["busy"].get<uint64_t>()) << name;
    EXPECT_EQ(est.stages[s].transactions_out, st["transactions_out"].get<uint64_t>()) << name;
  }
  const nlohmann::json ej = est.to_json();
  for (const char* key : {"triangles_in", "triangles_culled", "tiles_visited", "pixel_tests", "fragments", "samples",
                          "sample_tests", "samples_covered", "pixels_partially_covered", "fragments_shaded",
                          "rop_accesses", "framebuffer_bytes", "resolve_cycles", "resolve_bytes"})
    EXPECT_EQ(ej[key], sim[key]) << key;
  return true;
}

std::vector<std::string> files_in(const std::string& dir, const std::string& ext) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RASTSIM_SOURCE_DIR) + "/" + dir))
    if (e.path().extension() == ext) out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ScEstimate, ShippedTracesAndConfigs) {
  const std::vector<std::string> configs = files_in("configs", ".toml");
  const std::vector<std::string> traces = shipped_traces();  // traces/*.trace, traces/2d/ and traces/3d/
  ASSERT_GE(configs.size(), 4u);
  ASSERT_GE(traces.size(), 5u);
  for (const std::string& config_path : configs) {
    Config cfg;
    cfg.load_file(config_path);
    // The analytic model's stage arithmetic against SystemC's, both bounds: with the fixed
    // per-access costs (memory.model = dram has no upper bound and adds the fills' waits;
    // DramBoundsOnShippedTracesAndConfigs below checks the shipped configs' dram).
    cfg.apply_override("memory.model=fixed");
    cfg.validate();
    for (const std::string& trace : traces) {
      SCOPED_TRACE(config_path + " x " + trace);
      EXPECT_TRUE(check_against_systemc(load_trace(trace), cfg));
    }
  }
}

TEST(ScEstimate, RandomScenesEveryTraversalAndSmallFifos) {
  const std::vector<std::string> one_entry = {
      "fifo.command_depth=1", "fifo.triangle_depth=1", "fifo.setup_depth=1", "fifo.tile_depth=1",
      "fifo.pixel_depth=1",   "fifo.fragment_depth=1", "fifo.draw2d_depth=1", "fifo.op2d_depth=1"};
  for (const char* traversal : {"tiled", "bbox", "hierarchical", "scanline"}) {
    for (bool small_fifos : {false, true}) {
      for (uint64_t seed : {1, 2}) {
        SCOPED_TRACE(std::string(traversal) + (small_fifos ? " fifos=1" : "") + " seed " + std::to_string(seed));
        std::vector<std::string> sets = {std::string("raster.traversal=") + traversal, "raster.tile_size=8",
                                         "raster.hier_levels=32/8/2", "coarse.tiles_per_cycle=2",
                                         "setup.latency_cycles=20", "interp.latency_cycles=9"};
        if (small_fifos) sets.insert(sets.end(), one_entry.begin(), one_entry.end());
        const Config cfg = make_config(sets);
        EXPECT_TRUE(check_against_systemc(random_scene(seed * 101, 96, 80, 60), cfg));
        EXPECT_TRUE(check_against_systemc(parse_trace(testing::random_2d_trace(seed * 7, 96, 80, 40), "random_2d"), cfg));
      }
    }
  }
}

// Multisampling: fine tests x S, ROP accesses from the masks, the end-of-frame marker
// and the resolve pass, in both aa modes, with every exact traversal (scanline takes
// one sample only) and with one-entry FIFOs.
TEST(ScEstimate, RandomScenesWithSamples) {
  const std::vector<std::string> one_entry = {"fifo.command_depth=1", "fifo.triangle_depth=1", "fifo.setup_depth=1",
                                              "fifo.tile_depth=1",    "fifo.pixel_depth=1",    "fifo.fragment_depth=1"};
  for (int samples : {4, 8}) {
    for (const char* mode : {"msaa", "ssaa"}) {
      for (const char* traversal : {"tiled", "bbox", "hierarchical"}) {
        const bool small_fifos = std::string(traversal) == "tiled";
        SCOPED_TRACE(std::to_string(samples) + " " + mode + " " + traversal + (small_fifos ? " fifos=1" : ""));
        std::vector<std::string> sets = {"raster.samples=" + std::to_string(samples), std::string("raster.aa_mode=") + mode,
                                         std::string("raster.traversal=") + traversal, "raster.tile_size=8",
                                         "raster.hier_levels=32/8/2", "coarse.tiles_per_cycle=2",
                                         "setup.latency_cycles=20", "interp.latency_cycles=9"};
        if (small_fifos) sets.insert(sets.end(), one_entry.begin(), one_entry.end());
        const Config cfg = make_config(sets);
        EXPECT_TRUE(check_against_systemc(random_scene(uint64_t(samples) * 13 + 1, 96, 80, 50), cfg));
      }
    }
  }
  // The shipped triangle traces (not the 2D ones, an error with samples > 1 at both
  // levels) at 4 samples.
  for (const std::string& trace : shipped_traces()) {
    if (trace.find("/2d/") != std::string::npos) continue;
    SCOPED_TRACE(trace);
    const Scene scene = load_trace(trace);
    std::vector<std::string> sets{"raster.samples=4", "raster.out_of_range=cull"};
    for (const auto& c : scene.commands)
      if (const auto* v = std::get_if<CmdViewport>(&c.body)) {
        sets.push_back("display.width=" + std::to_string(std::max(128, v->width)));
        sets.push_back("display.height=" + std::to_string(std::max(128, v->height)));
      }
    EXPECT_TRUE(check_against_systemc(scene, make_config(sets)));
  }
}

// A scene the geometry front end bounds (clip_cube is the ROP's): n small clip-space
// triangles, as single tri4 commands (every third with a vertex behind the near plane:
// two new vertices, two triangles out) or as one strip zigzagging across the viewport
// (every fifth vertex behind the near plane).
std::string small_clip_triangles(uint64_t seed, int n, bool strip) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> centre(-0.9, 0.9), jitter(-0.05, 0.05), depth(0.1, 0.9);
  const auto v4 = [](double x, double y, double z) {
    return std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + " 1";
  };
  std::string out;
  if (strip) {
    out = "strip\n";
    for (int i = 0; i < n + 2; ++i)
      out += "v4 " + v4(-0.9 + 1.8 * i / (n + 2), (i % 2 ? 0.05 : -0.05) + jitter(rng), i % 5 ? depth(rng) : -0.3) + "\n";
    return out + "end\n";
  }
  for (int i = 0; i < n; ++i) {
    const double cx = centre(rng), cy = centre(rng);
    out += "tri4";
    for (int k = 0; k < 3; ++k) out += "  " + v4(cx + jitter(rng), cy + jitter(rng), (i % 3 || k) ? depth(rng) : -0.3);
    out += "\n";
  }
  return out;
}

TEST(ScEstimate, FrontEndBoundClipSpaceScenes) {
  for (const bool strip : {true, false}) {
    const Scene scene = parse_trace(small_clip_triangles(0xfe, 150, strip), "small_clip");
    SCOPED_TRACE(strip ? "one strip" : "tri4 commands");
    EXPECT_TRUE(check_against_systemc(scene, make_config({})));
    EXPECT_TRUE(check_against_systemc(
        scene, make_config({"fifo.clip_command_depth=1", "fifo.screen_depth=1", "fifo.command_depth=1",
                            "front_end.clip_cycles_per_vertex=9", "front_end.latency_cycles=11"})));
  }
}

TEST(ScEstimate, StallsChangeNoBusyTotal) {
  sc::SimOptions opts;
  opts.stall_seed = 5;
  opts.stall_probability = 0.3;
  EXPECT_TRUE(check_against_systemc(parse_trace(testing::random_2d_trace(11, 96, 80, 30), "random_2d"),
                                    make_config({"fifo.tile_depth=1"}), opts, false));
}

// memory.model = "dram" on `cfg`: SystemC's cycles >= the lower bound (its stage and
// bandwidth parts), its DRAM's last completion >= the bytes read and written / peak; the
// bytes are render's; every stage's busy equals SystemC's but the ROP's (which waits
// for its line fills); no upper bound.
void check_dram_bounds(const Scene& scene, const Config& cfg) {
  const nlohmann::json sim = run_isolated([&] { return simulate_stats(scene, cfg); });
  ASSERT_FALSE(sim.contains("error")) << sim["error"];
  const EstimateResult est = estimate_scene(scene, ArchParams::resolve(cfg));
  const uint64_t cycles = sim["cycles"];
  EXPECT_LE(est.cycles_lower_bound, cycles);
  EXPECT_EQ(est.cycles_lower_bound, std::max(est.stage_lower_bound, est.bandwidth_lower_bound));
  // SystemC's own cycles_lower_bound sums its busy cycles, the ROP's fill waits included.
  EXPECT_LE(est.stage_lower_bound, sim["cycles_lower_bound"].get<uint64_t>());
  EXPECT_LE(est.dram_lower_bound, std::max(cycles, sim["memory"]["dram"]["end_cycle"].get<uint64_t>()));
  EXPECT_EQ(est.dram_bytes_read, sim["dram_bytes_read"].get<uint64_t>());
  EXPECT_EQ(est.dram_bytes_written, sim["dram_bytes_written"].get<uint64_t>());
  EXPECT_FALSE(est.has_upper_bound());
  EXPECT_TRUE(est.to_json()["cycles_upper_bound"].is_null());
  for (size_t s = 0; s < kStageCount; ++s) {
    const std::string name(kStages[s].name);
    const uint64_t busy = sim["stages"][name]["busy"];
    if (kStages[s].id == StageId::Rop)
      EXPECT_LE(est.stages[s].busy, busy) << name;
    else
      EXPECT_EQ(est.stages[s].busy, busy) << name;
  }
}

// Every shipped config with its own memory (preset, layout, caches, fast clear; desktop's
// GDDR6 and fast clear make its 1080p frames about 0.2 s a run).
TEST(ScEstimate, DramBoundsOnShippedTracesAndConfigs) {
  for (const std::string& config_path : files_in("configs", ".toml")) {
    Config cfg;
    cfg.load_file(config_path);
    cfg.apply_override("memory.model=dram");
    cfg.apply_override("raster.depth_func=less");
    cfg.validate();
    for (const std::string& trace : shipped_traces()) {
      if (trace.find("/2d/") != std::string::npos || trace.find("/3d/") != std::string::npos) continue;
      SCOPED_TRACE(config_path + " x " + trace);
      check_dram_bounds(load_trace(trace), cfg);
    }
  }
}

// A full-screen quad, depth test on, no fast clear: every 64-byte line of both surfaces
// (128 x 128 x 4 bytes each) is filled once, 131072 bytes read. At dram.clock_mhz = 10
// the DDR4 channel's peak is 8 bytes x 2 transfers x 10 MHz = 160 MB/s, 0.32 bytes a
// 500 MHz core cycle: the bound is 131072 / 0.32 = 409600 cycles, far above any stage's.
TEST(ScEstimate, DramBandwidthBoundBindsOnASlowDram) {
  const Scene quad = parse_trace(
      "viewport 128 128\nclear 0 0 0\n"
      "tri 0 0 0.5 255 0 0  0 128 0.5 255 0 0  128 0 0.5 255 0 0\n"
      "tri 128 0 0.5 0 255 0  0 128 0.5 0 255 0  128 128 0.5 0 255 0\n",
      "quad");
  const Config cfg = make_config({"memory.model=dram", "raster.depth_func=less", "dram.clock_mhz=10"});
  const EstimateResult est = estimate_scene(quad, ArchParams::resolve(cfg));
  EXPECT_EQ(est.dram_bytes_read, 131072u);
  EXPECT_DOUBLE_EQ(est.dram_peak_bytes_per_cycle, 0.32);
  EXPECT_EQ(est.bandwidth_lower_bound, 409600u);
  EXPECT_EQ(est.cycles_lower_bound, 409600u);
  EXPECT_LT(est.stage_lower_bound, 409600u);
  check_dram_bounds(quad, cfg);
}

TEST(ScEstimate, EmptySceneIsZero) {
  const EstimateResult r = estimate_scene(Scene{}, ArchParams::resolve(Config{}));
  EXPECT_EQ(r.cycles_lower_bound, 0u);
  EXPECT_EQ(r.cycles_upper_bound, 0u);
  EXPECT_EQ(r.cycles_estimate, 0u);
}

}  // namespace
}  // namespace rastsim::sctest

namespace rastsim::sctest {
namespace {

// The measured table of docs/estimate.md (not a check; disabled unless asked for):
//   rastsim_sc_tests --gtest_also_run_disabled_tests --gtest_filter='*EstimateTable'
// Per shipped trace x config: the bounds, the estimate, SystemC's cycles, the
// estimate's error, and the median of 3 wall times of each level's own work
// (estimate_scene vs simulate_scene's sim_wall_seconds, scene parsing excluded).
TEST(ScEstimate, DISABLED_EstimateTable) {
  std::printf("| trace | config | lower | estimate | upper | SystemC | estimate error | (SystemC-lower)/(upper-lower) "
              "| estimate wall | simulate wall | ratio |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const auto median3 = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[1];
  };
  for (const std::string& trace : shipped_traces()) {
    for (const std::string& config_path : files_in("configs", ".toml")) {
      Config cfg;
      cfg.load_file(config_path);
      cfg.validate();
      const Scene scene = load_trace(trace);
      std::vector<double> est_wall, sim_wall;
      EstimateResult est;
      uint64_t cycles = 0;
      for (int run = 0; run < 3; ++run) {
        est = estimate_scene(scene, ArchParams::resolve(cfg));
        const nlohmann::json sim = run_isolated([&] { return simulate_stats(scene, cfg); });
        ASSERT_FALSE(sim.contains("error")) << sim["error"];
        cycles = sim["cycles"];
        est_wall.push_back(est.wall_seconds);
        sim_wall.push_back(sim["sim_wall_seconds"]);
      }
      const double te = median3(est_wall), ts = median3(sim_wall);
      const double gap = double(est.cycles_upper_bound - est.cycles_lower_bound);
      std::printf("| %s | %s | %llu | %llu | %llu | %llu | %+.1f %% | %.2f | %.3f ms | %.3f ms | %.0fx |\n",
                  std::filesystem::path(trace).filename().c_str(),
                  std::filesystem::path(config_path).stem().c_str(), (unsigned long long)est.cycles_lower_bound,
                  (unsigned long long)est.cycles_estimate, (unsigned long long)est.cycles_upper_bound,
                  (unsigned long long)cycles, 100.0 * (double(est.cycles_estimate) - double(cycles)) / double(cycles),
                  gap > 0 ? (double(cycles) - double(est.cycles_lower_bound)) / gap : 0.0, te * 1e3, ts * 1e3,
                  ts / te);
    }
  }
}

}  // namespace
}  // namespace rastsim::sctest
