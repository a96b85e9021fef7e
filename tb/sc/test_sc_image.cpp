// SPDX-License-Identifier: Apache-2.0
// The timed model's image and fragment stream equal the reference model's: shipped
// traces and random scenes, several tile sizes and coordinate formats, FIFOs of depth
// 1, and random stall injection.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "common/random_2d_trace.h"
#include "sim_harness.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

// (tile size, coordinate format)
using Arch = std::tuple<int, std::string>;

class ScImage : public ::testing::TestWithParam<Arch> {
 protected:
  Config config(std::vector<std::string> extra = {}) const {
    extra.push_back("raster.tile_size=" + std::to_string(std::get<0>(GetParam())));
    extra.push_back("raster.coord_format=" + std::get<1>(GetParam()));
    return make_config(extra);
  }
};

TEST_P(ScImage, RandomScenesMatchReference) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = random_scene(seed, 128, 96, 60);
    const Config cfg = config({seed == 2 ? "raster.depth_func=less" : "raster.cull=back"});
    expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg); }));
  }
}

TEST_P(ScImage, ShippedTracesMatchReference) {
  const auto traces = shipped_traces();
  ASSERT_FALSE(traces.empty());
  size_t skipped = 0;
  for (const auto& path : traces) {
    SCOPED_TRACE(path);
    Scene scene;
    try {
      scene = load_trace(path);
    } catch (const SceneError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    // A trace's viewport may be larger than the default display: size the display to it.
    std::vector<std::string> extra{"raster.depth_func=less", "raster.out_of_range=cull"};
    for (const auto& c : scene.commands)
      if (const auto* v = std::get_if<CmdViewport>(&c.body)) {
        extra.push_back("display.width=" + std::to_string(std::max(128, v->width)));
        extra.push_back("display.height=" + std::to_string(std::max(128, v->height)));
      }
    Config cfg;
    try {
      cfg = config(extra);
    } catch (const ConfigError& e) {
      // Only one reason to skip: the trace's viewport does not fit this coordinate
      // format (Config::validate names raster.coord_format). Anything else fails.
      const std::string why = e.what();
      if (why.find("raster.coord_format") == std::string::npos) {
        ADD_FAILURE() << "config does not validate: " << why;
        continue;
      }
      std::cout << "skipped " << path << " under " << std::get<1>(GetParam()) << ": " << why << "\n";
      ++skipped;
      continue;
    }
    expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg); }));
  }
  EXPECT_LT(skipped, traces.size()) << "every shipped trace was skipped";
}

INSTANTIATE_TEST_SUITE_P(TileSizesAndFormats, ScImage,
                         ::testing::Combine(::testing::Values(4, 8, 16, 64),
                                            ::testing::Values(std::string("s7.16"), std::string("s11.4"))),
                         [](const auto& info) {
                           std::string f = std::get<1>(info.param);
                           f.erase(std::remove(f.begin(), f.end(), '.'), f.end());
                           return "Tile" + std::to_string(std::get<0>(info.param)) + "_" + f;
                         });

// 2D commands mixed with triangles (tb/common/random_2d_trace.h): the timed model's
// image and counters equal the reference's for every line method, with 1-deep FIFOs on
// the 2D path and random stalls.
class ScImage2d : public ::testing::TestWithParam<std::string> {};

TEST_P(ScImage2d, RandomMixedScenesMatchReference) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = parse_trace(testing::random_2d_trace(seed, 96, 80, 60), "random_2d");
    std::vector<std::string> extra{"line.method=" + GetParam(), "display.width=96", "display.height=80"};
    if (seed % 2 == 0) extra.insert(extra.end(), {"fifo.draw2d_depth=1", "fifo.op2d_depth=1", "fifo.command_depth=1"});
    if (seed % 3 == 0) extra.insert(extra.end(), {"engine2d.fill_pixels_per_cycle=1", "engine2d.span_setup_cycles=0"});
    sc::SimOptions stalls;
    if (seed == 5) {
      stalls.stall_seed = seed;
      stalls.stall_probability = 0.3;
    }
    const Config cfg = make_config(extra);
    expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg, stalls); }));
  }
}

INSTANTIATE_TEST_SUITE_P(LineMethods, ScImage2d, ::testing::Values("diamond", "bresenham", "midpoint", "dda"));

// interp.method = dda: the timed model's interpolation stage calls the same reference
// function, so image, depth, fragments and the error stats equal the reference's.
class ScInterpDda : public ::testing::TestWithParam<std::string> {};

TEST_P(ScInterpDda, RandomScenesMatchReference) {
  for (uint64_t seed : {4u, 5u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = random_scene(seed, 128, 96, 60);
    const Config cfg = make_config({"interp.method=dda", "interp.dda_arith=" + GetParam(), "raster.depth_func=less"});
    expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg); }));
  }
}

INSTANTIATE_TEST_SUITE_P(Arith, ScInterpDda, ::testing::Values("f32", "fixed"));

TEST(ScFifo, DepthOneNeverLosesOrReorders) {
  // Every FIFO one entry deep (and no pipeline latency slots: no reciprocal unit either): maximal backpressure.
  // Link::read checks the sequence numbers and simulate_scene checks writes == reads; the fragment stream must match.
  const Config cfg = make_config({"fifo.command_depth=1", "fifo.triangle_depth=1", "fifo.setup_depth=1",
                                  "fifo.tile_depth=1", "fifo.pixel_depth=1", "fifo.fragment_depth=1",
                                  "fifo.draw2d_depth=1", "fifo.op2d_depth=1", "fifo.clip_command_depth=1",
                                  "fifo.screen_depth=1", "fifo.texture_depth=1", "front_end.latency_cycles=0",
                                  "raster.tile_size=8", "setup.latency_cycles=2", "interp.latency_cycles=0",
                                  "interp.perspective=false"});
  const Scene scene = random_scene(11, 128, 128, 80);
  const auto r = run_isolated([&] { return compare_with_reference(scene, cfg); });
  expect_matches_reference(r);
  for (const auto& [name, f] : r["stats"]["fifos"].items()) EXPECT_EQ(f["depth"], 1) << name;
}

TEST(ScFifo, RandomStallsDoNotChangeImage) {
  // A new seed each run (RASTSIM_STALL_SEED replays one); printed, and named on failure.
  const char* replay = std::getenv("RASTSIM_STALL_SEED");
  const uint64_t seed = replay ? std::strtoull(replay, nullptr, 10) : std::random_device{}();
  std::cout << "stall injection seed " << seed << " (rastsim simulate --stall-seed " << seed << ")\n";
  SCOPED_TRACE("stall injection seed " + std::to_string(seed) + " (replay: RASTSIM_STALL_SEED=" +
               std::to_string(seed) + ")");
  const Config cfg = make_config({"raster.tile_size=8", "raster.depth_func=lequal"});
  const Scene scene = random_scene(12, 128, 128, 80);
  sc::SimOptions stalls;
  stalls.stall_seed = seed;
  stalls.stall_probability = 0.3;
  const auto calm = run_isolated([&] { return simulate_stats(scene, cfg); });
  const auto r = run_isolated([&] { return compare_with_reference(scene, cfg, stalls); });
  expect_matches_reference(r);
  ASSERT_FALSE(calm.contains("error")) << calm["error"];
  EXPECT_GT(r["stats"]["cycles"].get<uint64_t>(), calm["cycles"].get<uint64_t>()) << "stalls had no effect";
}

TEST(ScVcd, TracesFifoOccupancyAndStageState) {
  const auto path = std::filesystem::temp_directory_path() / ("rastsim_sc_" + std::to_string(getpid()) + ".vcd");
  sc::SimOptions o;
  o.vcd_path = path.string();
  const Scene scene = random_scene(13, 64, 64, 10);
  const auto r = run_isolated([&] { return simulate_stats(scene, Config{}, o); });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  std::ifstream is(path);
  const std::string vcd((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  // sc_trace splits "tile_fifo.occupancy" into a scope and a variable.
  for (const char* scope : {"tile_fifo", "fragment_fifo", "fine_raster", "rop"})
    EXPECT_NE(vcd.find(std::string("$scope module ") + scope + " $end"), std::string::npos) << scope;
  EXPECT_NE(vcd.find(" occupancy [31:0]"), std::string::npos);
  EXPECT_NE(vcd.find(" state [31:0]"), std::string::npos);
}

}  // namespace
}  // namespace rastsim::sctest
