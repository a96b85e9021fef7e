// SPDX-License-Identifier: Apache-2.0
// pipeline.mode = binned in the timed model (sc/binning.h; docs/binning.md, "Timed model"):
//
// - on random scenes with mid-frame clears, scissors and viewports, every bin size 8 ..
//   128 (and oblong 8 x 128, 64 x 16), 1 and 4 samples, with a parameter buffer that holds
//   the frame and one of 4 KiB that overflows: simulate's image, depth, fragment stream
//   and every render counter (bins, primitives_per_bin_mean, bin_overflows,
//   dram_bytes_geometry, dram_bytes_framebuffer included) equal render's in binned mode,
//   and the image equals immediate mode's (render, independent of the binner);
// - with memory.model = dram the same, every memory client's counts included (binning,
//   tile_store, and the ROP's moving nothing), and the DRAM model saw requests of both
//   binned clients;
// - cycles: every stage's busy + stalled + starved equals the run's cycles (the binner
//   too), the binner's transactions are the triangles and state items setup sent it, and
//   an overflowing buffer costs cycles (the extra pass's loads and stores);
// - early and hierarchical Z are refused with a clear message.
#include <gtest/gtest.h>

#include "config/arch_params.h"
#include "config/raster_state_config.h"
#include "report/stats_json.h"
#include "ref/pipeline.h"
#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

struct BinCase {
  int w, h, samples;
  bool overflow;
  std::string name() const {
    return std::to_string(w) + "x" + std::to_string(h) + " S=" + std::to_string(samples) +
           (overflow ? " overflow" : "");
  }
  std::vector<std::string> keys() const {
    return {"pipeline.mode=binned",
            "bin.width=" + std::to_string(w),
            "bin.height=" + std::to_string(h),
            "raster.samples=" + std::to_string(samples),
            "raster.depth_func=less",
            "display.width=150",
            "display.height=110",
            "bin.tile_buffer_bytes=1048576",  // a 128 x 128 bin at 4 samples
            "bin.parameter_buffer_bytes=" + std::to_string(overflow ? 4096 : 16 << 20)};
  }
};

std::vector<BinCase> bin_cases() {
  std::vector<BinCase> out;
  for (int samples : {1, 4})
    for (bool overflow : {false, true}) {
      for (int size : {8, 16, 32, 64, 128}) out.push_back({size, size, samples, overflow});
      out.push_back({8, 128, samples, overflow});
      out.push_back({64, 16, samples, overflow});
    }
  return out;
}

// The immediate reference's image of `scene` under `keys` with pipeline.mode = immediate.
uint32_t immediate_crc(const Scene& scene, std::vector<std::string> keys) {
  keys.front() = "pipeline.mode=immediate";
  RenderStats s;
  return render_scene(scene, raster_state_from_config(make_config(keys)), s).color_crc32();
}

TEST(ScBinning, RandomScenesSameAsRender) {
  const Scene scene = random_scene(29, 150, 110, 160);
  for (const BinCase& c : bin_cases()) {
    SCOPED_TRACE(c.name());
    const nlohmann::json r = run_isolated([&, cfg = make_config(c.keys())] { return compare_with_reference(scene, cfg); });
    expect_matches_reference(r);
    ASSERT_FALSE(r.contains("error"));
    EXPECT_EQ(r["crc_sim"].get<uint32_t>(), immediate_crc(scene, c.keys()));
    const nlohmann::json& s = r["stats"];
    EXPECT_EQ(s["bin_overflows"].get<uint64_t>() > 0, c.overflow) << s["bin_overflows"];
    // The binner takes every triangle setup accepts and every state item (end of frame included).
    EXPECT_EQ(s["stages"]["binner"]["transactions_in"], s["fifos"]["setup_fifo"]["transactions"]);
    EXPECT_GT(s["stages"]["binner"]["busy"].get<uint64_t>(), 0u);
  }
}

TEST(ScBinning, MemoryClientsSameAsRender) {
  const Scene scene = random_scene(30, 150, 110, 120);
  for (const BinCase& c : bin_cases()) {
    if (c.w != c.h) continue;
    SCOPED_TRACE(c.name());
    std::vector<std::string> keys = c.keys();
    keys.push_back("memory.model=dram");
    keys.push_back("memory.fb_layout=tiled");
    const nlohmann::json r = run_isolated([&, cfg = make_config(keys)] { return render_and_simulate(scene, cfg); });
    ASSERT_FALSE(r.contains("error")) << r["error"];
    EXPECT_EQ(r["sim"], r["ref"]);
    const nlohmann::json& ref = r["ref"];
    const nlohmann::json& clients = ref["memory"]["clients"];
    EXPECT_EQ(clients["binning"]["bytes_read"].get<uint64_t>() + clients["binning"]["bytes_written"].get<uint64_t>(),
              ref["dram_bytes_geometry"].get<uint64_t>());
    EXPECT_EQ(clients["tile_store"]["bytes_read"].get<uint64_t>() +
                  clients["tile_store"]["bytes_written"].get<uint64_t>(),
              ref["dram_bytes_framebuffer"].get<uint64_t>());
    EXPECT_EQ(clients["rop_color"]["bytes_written"], 0);
    // The timed memory system carried both binned clients' requests.
    const nlohmann::json& dram_clients = r["stats"]["memory"]["clients"];
    EXPECT_GT(dram_clients["binning"]["bursts_written"].get<uint64_t>(), 0u);
    EXPECT_GT(dram_clients["binning"]["bursts_read"].get<uint64_t>(), 0u);
    EXPECT_GT(dram_clients["tile_store"]["bursts_written"].get<uint64_t>(), 0u);
  }
}

TEST(ScBinning, OverflowCostsCycles) {
  const Scene scene = random_scene(31, 150, 110, 160);
  for (bool dram : {false, true}) {
    SCOPED_TRACE(dram ? "dram" : "fixed");
    uint64_t cycles[2] = {};
    for (bool overflow : {false, true}) {
      std::vector<std::string> keys = BinCase{32, 32, 1, overflow}.keys();
      if (dram) keys.push_back("memory.model=dram");
      const nlohmann::json r = run_isolated([&, cfg = make_config(keys)] { return simulate_stats(scene, cfg); });
      ASSERT_FALSE(r.contains("error")) << r["error"];
      cycles[overflow] = r["cycles"];
    }
    EXPECT_GT(cycles[1], cycles[0]);
  }
}

// A colour clear on a 64 x 64 screen, 32 x 32 bins (4), memory.model = fixed, worked by
// hand from docs/binning.md's table (R = 64 bytes, 64 clear pixels a cycle): each bin a
// begin marker (no load: 1), its clear (1024 / 64 = 16) and its store (4096 / 64 = 64):
// the ROP 4 x 81 + 1 (end of frame) = 325 busy cycles; the binner 1 (viewport) + 1
// (clear) + 1 (end of frame) + 4 x 3 (markers) + 1 (its pass on) = 16.
TEST(ScBinning, HandWorkedCycles) {
  Scene scene;
  scene.commands.push_back({CmdViewport{64, 64}, {"hand", 1}});
  scene.commands.push_back({CmdClear{10, 20, 30}, {"hand", 2}});
  const nlohmann::json r = run_isolated([&, cfg = make_config({"pipeline.mode=binned", "display.width=64",
                                                               "display.height=64", "rop.clear_pixels_per_cycle=64",
                                                               "rop.resolve_bytes_per_cycle=64"})] {
    return simulate_stats(scene, cfg);
  });
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["stages"]["rop"]["busy"], 325);
  EXPECT_EQ(r["stages"]["rop"]["transactions_in"], 13);
  EXPECT_EQ(r["stages"]["binner"]["busy"], 16);
  EXPECT_EQ(r["dram_bytes_framebuffer"], 64 * 64 * 4);
}

TEST(ScBinning, EarlyAndHierarchicalZRefused) {
  const Scene scene = random_scene(32, 64, 64, 10);
  for (const char* key : {"depth.early=true", "depth.hiz=minmax"}) {
    SCOPED_TRACE(key);
    const nlohmann::json r = run_isolated([&, cfg = make_config({"pipeline.mode=binned", "raster.depth_func=less", "display.width=64", "display.height=64", key})] {
      return simulate_stats(scene, cfg);
    });
    ASSERT_TRUE(r.contains("error"));
    EXPECT_NE(r["error"].get<std::string>().find("pipeline.mode = binned with depth.early or depth.hiz"),
              std::string::npos)
        << r["error"];
  }
}

}  // namespace
}  // namespace rastsim::sctest
