// SPDX-License-Identifier: Apache-2.0
// `rastsim area`: the hierarchical sums by hand (no Yosys), then Yosys on the fine
// raster of a deliberately small parameter set (16 px display, s4.2, 4 px tiles, about
// 10 CPU seconds a synthesis): the JSON keys, positive counts, more lanes giving more
// cells (monotonicity, an independent sanity check of the flow), the cache hit, and the
// command line's errors; the split synthesis against one process.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common.h"
#include "util/process.h"
#include "rtlsim/area.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

fs::path temp_path(const std::string& name) {
  return fs::temp_directory_path() / ("rastsim_area_tests_" + std::to_string(::getpid()) + "_" + name);
}

bool have_yosys() {
  try {
    find_yosys();
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

// The small parameter set; `lanes` is fine.samples_per_cycle.
app::ConfigOptions small_config(int lanes) {
  app::ConfigOptions c;
  // interp.perspective off: the reciprocal lanes are wide multipliers (tens of minutes of Yosys);
  // their area is measured by the AreaRecip tests and docs/area.md, not here. Two samples
  // (the RTL's minimum): a --top stage is elaborated inside rast_top, whose ROP access
  // buffer at 16 samples took Yosys' `hierarchy` 69 of a run's 79 s.
  c.sets = {"display.width=16", "display.height=16", "raster.coord_format=s4.2", "raster.tile_size=4", "interp.perspective=false",
            "raster.max_samples=2", "fine.samples_per_cycle=" + std::to_string(lanes)};
  return c;
}

// Runs `rastsim ARGS` (argv, no shell) with `env` (NAME=VALUE, through env(1)) added to
// its environment; returns the exit status, stdout+stderr in `out`.
int run_cli(const std::vector<std::string>& args, std::string& out, const std::vector<std::string>& env = {}) {
  std::vector<std::string> argv{"env"};
  argv.insert(argv.end(), env.begin(), env.end());
  argv.push_back(RASTSIM_BINARY);
  argv.insert(argv.end(), args.begin(), args.end());
  ProcessOptions o;
  o.out = Sink::Capture;
  o.err = Sink::Stdout;
  const ProcessResult r = run_process(argv, o);
  out = r.out;
  return WIFEXITED(r.status) ? WEXITSTATUS(r.status) : -1;
}

// A hand-made `stat -json` of top { 2 AND, 1 DFF, 3 x leaf, 1 x mid { 1 XOR, 1 x leaf } },
// leaf { 1 NOT, 2 DFF }: the totals worked out by hand below.
TEST(AreaStat, SumsSubmodulesByHand) {
  const nlohmann::json stat = nlohmann::json::parse(R"({
    "modules": {
      "\\top": {"num_cells_by_type": {"$_AND_": 2, "$_DFF_P_": 1, "$paramod$ab\\leaf": 3, "\\mid": 1},
                "estimated_num_transistors": "28+"},
      "\\mid": {"num_cells_by_type": {"$_XOR_": 1, "$paramod$ab\\leaf": 1}, "estimated_num_transistors": "12+"},
      "$paramod$ab\\leaf": {"num_cells_by_type": {"$_NOT_": 1, "$_DFF_P_": 2}, "estimated_num_transistors": "34"}
    }})");
  const AreaReport r = area_from_yosys_stat(stat, "top");
  // top: own 3 + 3 leaves of 3 + mid (1 + a leaf of 3) = 16 cells.
  EXPECT_EQ(r.total.cells, 16u);
  EXPECT_EQ(r.total.flip_flops, 1u + 3 * 2 + 2);
  EXPECT_EQ(r.total.transistors, 28u + 3 * 34 + (12 + 34));
  EXPECT_EQ(r.total.cells_by_type.at("$_DFF_P_"), 9u);
  ASSERT_EQ(r.stages.size(), 3u);
  EXPECT_EQ(r.stages.at("leaf").instances, 3u);
  EXPECT_EQ(r.stages.at("leaf").cells, 9u);
  EXPECT_EQ(r.stages.at("mid").cells, 4u);
  EXPECT_EQ(r.stages.at("mid").transistors, 46u);
  EXPECT_EQ(r.stages.at("top_glue").cells, 3u);
  EXPECT_EQ(r.stages.at("top_glue").flip_flops, 1u);
  EXPECT_THROW(area_from_yosys_stat(stat, "absent"), std::runtime_error);
}

// Yosys 0.23 types an instance of a module without parameters by its bare name ("leaf"),
// while the module's id is "\leaf": still a submodule, not an unknown cell.
TEST(AreaStat, ParameterlessSubmoduleByBareName) {
  const nlohmann::json stat = nlohmann::json::parse(R"({
    "modules": {
      "\\top": {"num_cells_by_type": {"$_AND_": 1, "leaf": 2}, "estimated_num_transistors": "6+"},
      "\\leaf": {"num_cells_by_type": {"$_NOT_": 3}, "estimated_num_transistors": "6"}
    }})");
  const AreaReport r = area_from_yosys_stat(stat, "top");
  EXPECT_EQ(r.total.cells, 1u + 2 * 3);             // top's AND and two leaves of 3 NOT
  EXPECT_EQ(r.total.transistors, 6u + 2 * 6);
  EXPECT_EQ(r.stages.at("leaf").instances, 2u);
}

TEST(Area, StatsJsonKeysPositiveAndSecondCallFromCache) {
  if (!have_yosys()) GTEST_SKIP() << "yosys not installed";
  const fs::path cache = temp_path("cache");
  setenv("RASTSIM_CACHE", cache.c_str(), 1);
  app::AreaCommandOptions o;
  o.config = small_config(2);
  o.top = "rast_fine_raster";
  o.stats_path = temp_path("area.json").string();
  o.quiet = true;
  app::run_area_command(o);
  std::ifstream is(o.stats_path);
  const nlohmann::json j = nlohmann::json::parse(is);
  for (const char* k : {"cells", "flip_flops", "transistors"}) {
    SCOPED_TRACE(k);
    ASSERT_TRUE(j.contains(k));
    EXPECT_GT(j.at(k).get<int64_t>(), 0);
    EXPECT_GT(j.at("stages").at("rast_fine_raster").at(k).get<int64_t>(), 0);
  }
  EXPECT_FALSE(j.at("from_cache").get<bool>());
  EXPECT_EQ(j.at("parameters").at("FineSamplesPerCycle"), 2);
  // A CMOS transistor estimate is at least 2 transistors a cell (an inverter).
  EXPECT_GE(j.at("transistors").get<int64_t>(), 2 * j.at("cells").get<int64_t>());
  EXPECT_EQ(fs::exists(cache / "area" / (j.at("key").get<std::string>() + ".json")), true);

  const auto t0 = std::chrono::steady_clock::now();
  app::run_area_command(o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream is2(o.stats_path);
  const nlohmann::json j2 = nlohmann::json::parse(is2);
  EXPECT_TRUE(j2.at("from_cache").get<bool>());
  EXPECT_EQ(j2.at("cells"), j.at("cells"));
  EXPECT_EQ(j2.at("transistors"), j.at("transistors"));
  EXPECT_LT(s, 2.0) << "a cache hit runs only `yosys -V`";
  fs::remove_all(cache);
  fs::remove(o.stats_path);
}

// Independent of the numbers themselves: four sample lanes cannot take fewer gates than one.
TEST(Area, MoreFineLanesMoreCells) {
  if (!have_yosys()) GTEST_SKIP() << "yosys not installed";
  AreaOptions ao;
  ao.top = "rast_fine_raster";
  ao.use_cache = false;
  const auto area_of = [&](int lanes) { return synthesize_area(rtl_params(ArchParams::resolve(app::load_config(small_config(lanes)))), ao); };
  const AreaReport one = area_of(1), two = area_of(2);
  EXPECT_GT(two.total.cells, one.total.cells);
  EXPECT_GT(two.total.transistors, one.total.transistors);
  EXPECT_GE(two.total.flip_flops, one.total.flip_flops);
}

// A standalone --top root (no config parameter) synthesised without the cache.
AreaReport synthesize_root(const std::string& top) {
  AreaOptions ao;
  ao.top = top;
  ao.use_cache = false;
  return synthesize_area(rtl_params(ArchParams::resolve(app::load_config(small_config(1)))), ao);
}

// The front end's binary32 adder, a --top root of its own (no config parameter): its
// parameterless submodules (rast_fp32_unpack) count, and it holds no flip-flop. A lower
// bound, not its figure: a 28-bit adder, two shifters and a rounder take over 1,000 gates.
TEST(Area, Fp32AdderIsItsOwnRoot) {
  if (!have_yosys()) GTEST_SKIP() << "yosys not installed";
  const AreaReport r = synthesize_root("rast_fp32_add");
  EXPECT_GT(r.total.cells, 1000u);
  EXPECT_EQ(r.total.flip_flops, 0u);
  EXPECT_EQ(r.stages.count("rast_fp32_add"), 1u);
}

// The reciprocal unit (rtl/rast_recip.sv) at its defaults, 8 index bits and 2 steps, is a
// root of its own. Its flip-flops, counted by hand from the RTL (constant bits removed):
// 5 valid bits; the seed, 10 significant bits, and d, 40; step 1 (its y is the seed's 10
// bits): y 10, c 42, the new y 42, d twice 40; step 2: y 42, c 42, the new y 42. 355.
TEST(Area, ReciprocalUnitIsItsOwnRoot) {
  if (!have_yosys()) GTEST_SKIP() << "yosys not installed";
  const AreaReport r = synthesize_root("rast_recip");
  EXPECT_EQ(r.total.flip_flops, 5u + 10 + 40 + (10 + 42 + 42 + 2 * 40) + (42 + 42 + 42));
  EXPECT_GT(r.total.cells, 10000u);  // four multipliers of 40 to 42 bits, two of them by a 10-bit seed
  EXPECT_EQ(r.stages.count("rast_recip"), 1u);
}

// The split synthesis (one Yosys process a module of rast_top, submodules as blackboxes,
// sums taken in C++) against one process holding the whole hierarchy, on the smallest
// pipeline (16 px display, s4.2, 4 px tiles, one fine and one fragment lane, 2 samples,
// narrow buses, 2-entry FIFOs): flops and the set of stages equal, cells and transistors
// within a tolerance. The flow never flattens, so the two runs differ only in ABC's result
// on each module (the same logic, netlists in another order). Measured on this design
// (Yosys 0.23): the whole +0.28 % cells, +0.49 % transistors; the worst stage
// rast_coarse_raster +1.37 % cells, +1.40 % transistors. The tolerances leave room
// (docs/area.md, "Split synthesis").
constexpr double kSplitTotalTolerance = 0.01;
constexpr double kSplitStageTolerance = 0.025;

TEST(Area, SplitEqualsOneProcessWithinTolerance) {
  if (!have_yosys()) GTEST_SKIP() << "yosys not installed";
  app::ConfigOptions c = small_config(1);
  // Narrow buses and 2-entry FIFOs: about half the cells and Yosys time of the defaults
  // (the FIFOs carry every vertex's depth and texture coordinates); the flow is the same.
  for (const char* s : {"interp.fragments_per_cycle=1", "raster.max_samples=2", "raster.depth_bits=16",
                        "interp.texcoord_format=s1.4", "fifo.triangle_depth=2", "fifo.setup_depth=2",
                        "fifo.tile_depth=2", "fifo.pixel_depth=2"})
    c.sets.push_back(s);
  const RtlParams p = rtl_params(ArchParams::resolve(app::load_config(c)));
  const fs::path cache = temp_path("split_cache");
  AreaOptions ao;
  ao.top = "rast_top";
  ao.cache_dir = cache.string();
  const AreaReport split = synthesize_area(p, ao);
  ao.split = false;
  ao.use_cache = false;
  const AreaReport one = synthesize_area(p, ao);
  EXPECT_GT(split.modules, 10u);  // the stages, FIFOs, holds and their submodules
  EXPECT_EQ(one.modules, 1u);
  EXPECT_EQ(split.total.flip_flops, one.total.flip_flops);
  const auto near = [](uint64_t a, uint64_t b, double tolerance) {
    return std::abs(double(a) - double(b)) <= tolerance * double(b);
  };
  const auto pct = [](uint64_t a, uint64_t b) { return 100.0 * (double(a) - double(b)) / double(b); };
  std::printf("split (%zu modules) vs one process: cells %llu vs %llu (%+.2f %%), flip-flops %llu vs %llu, transistors "
              "%llu vs %llu (%+.2f %%)\n",
              size_t(split.modules), (unsigned long long)split.total.cells, (unsigned long long)one.total.cells,
              pct(split.total.cells, one.total.cells), (unsigned long long)split.total.flip_flops,
              (unsigned long long)one.total.flip_flops, (unsigned long long)split.total.transistors,
              (unsigned long long)one.total.transistors, pct(split.total.transistors, one.total.transistors));
  std::printf("CPU split %.0f s, one %.0f s; peak split %.0f MB, one %.0f MB\n", split.cpu_seconds, one.cpu_seconds,
              split.peak_mb, one.peak_mb);
  for (const auto& [name, s] : split.stages)
    if (one.stages.count(name))
      std::printf("  %s: cells %+.2f %%, transistors %+.2f %%\n", name.c_str(), pct(s.cells, one.stages.at(name).cells),
                  pct(s.transistors, one.stages.at(name).transistors));
  EXPECT_TRUE(near(split.total.cells, one.total.cells, kSplitTotalTolerance))
      << split.total.cells << " vs " << one.total.cells;
  EXPECT_TRUE(near(split.total.transistors, one.total.transistors, kSplitTotalTolerance))
      << split.total.transistors << " vs " << one.total.transistors;
  ASSERT_EQ(split.stages.size(), one.stages.size());
  for (const auto& [name, s] : split.stages) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(one.stages.count(name));
    const AreaCounts& o = one.stages.at(name);
    EXPECT_EQ(s.instances, o.instances);
    EXPECT_EQ(s.flip_flops, o.flip_flops);
    EXPECT_TRUE(near(s.cells, o.cells, kSplitStageTolerance)) << s.cells << " vs " << o.cells;
    EXPECT_TRUE(near(s.transistors, o.transistors, kSplitStageTolerance)) << s.transistors << " vs " << o.transistors;
  }
  // The whole is the sum of its stages (rast_top_glue is rast_top's own logic).
  uint64_t cells = 0, transistors = 0;
  for (const auto& [name, s] : split.stages) cells += s.cells, transistors += s.transistors;
  EXPECT_EQ(cells, split.total.cells);
  EXPECT_EQ(transistors, split.total.transistors);

  // Again: every module from the cache, the same figures.
  ao.split = true;
  ao.use_cache = true;
  const AreaReport again = synthesize_area(p, ao);
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(again.total.cells, split.total.cells);
  EXPECT_EQ(again.total.transistors, split.total.transistors);
  fs::remove_all(cache);
}

TEST(AreaCli, HelpBadConfigMissingYosys) {
  std::string out;
  EXPECT_EQ(run_cli({"area", "--help"}, out), 0);
  EXPECT_NE(out.find("--stats"), std::string::npos);
  EXPECT_NE(out.find("--top"), std::string::npos);
  EXPECT_NE(out.find("--one-process"), std::string::npos);
  EXPECT_NE(out.find("--jobs"), std::string::npos);

  EXPECT_NE(run_cli({"area", "--config", "/nonexistent/config.toml"}, out), 0);
  EXPECT_NE(out.find("/nonexistent/config.toml"), std::string::npos) << out;

  const fs::path bad = temp_path("bad.toml");
  std::ofstream(bad) << "[raster]\nno_such_key = 1\n";
  EXPECT_EQ(run_cli({"area", "--config", bad.string()}, out), 1);
  EXPECT_NE(out.find("no_such_key"), std::string::npos) << out;
  fs::remove(bad);

  // No yosys on PATH: the error names the Debian package.
  EXPECT_EQ(run_cli({"area", "--top", "rast_fine_raster"}, out, {"PATH=/nonexistent", "RASTSIM_YOSYS="}), 1);
  EXPECT_NE(out.find("package `yosys`"), std::string::npos) << out;

  EXPECT_EQ(run_cli({"area", "--top", "no_such_module"}, out), 1);
  EXPECT_NE(out.find("not an RTL module"), std::string::npos) << out;
}

}  // namespace
}  // namespace rastsim
