// SPDX-License-Identifier: Apache-2.0
// render --threads N: the parallel pipeline (triangles binned to screen regions, regions
// rasterized on N threads) must give the one-thread pipeline's framebuffer (colour and
// depth, every sample), CRC and stats, on random scenes for every shipped config, one
// sample and 4x msaa / ssaa, the three exact traversals, depth tests that make the
// triangle order visible, and state commands (clears, scissor) between the triangles.
// The one-thread pipeline is the reference the rest of the suite checks independently.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "common/random_vertex.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/traverse.h"
#include "report/stats_json.h"

namespace rastsim {
namespace {

// Runs of 300..700 triangles (the parallel path starts at 256) of 1..200 px, some off
// screen, with clears, depth clears and scissor changes between the runs.
Scene random_scene(std::mt19937& rng, int w, int h) {
  Scene sc;
  sc.source = "random";
  std::uniform_int_distribution<int> byte(0, 255), pct(0, 99);
  std::uniform_real_distribution<double> cx(-40, w + 40), cy(-40, h + 40), z(0, 1);
  for (int run = 0; run < 3; ++run) {
    if (run > 0) {
      CommandBody state;
      const int k = pct(rng);
      if (k < 35) state = CmdClear{uint8_t(byte(rng)), uint8_t(byte(rng)), uint8_t(byte(rng))};
      else if (k < 60) state = CmdClearDepth{z(rng)};
      else
        state = CmdScissor{pct(rng) < 70, std::uniform_int_distribution<int>(0, w / 2)(rng),
                           std::uniform_int_distribution<int>(0, h / 2)(rng), w / 2, h / 2};
      sc.commands.push_back({state, {"random", int(sc.commands.size()) + 1}});
    }
    const int n = std::uniform_int_distribution<int>(300, 700)(rng);
    CmdPrimitives p;
    for (int t = 0; t < n; ++t) {
      const double x = cx(rng), y = cy(rng);
      const double r = pct(rng) < 90 ? std::uniform_real_distribution<double>(0.5, 20)(rng)
                                     : std::uniform_real_distribution<double>(20, 200)(rng);
      for (int v = 0; v < 3; ++v) {
        p.vertices.push_back(test::random_vertex_on_circle(rng, x, y, r));
      }
    }
    sc.commands.push_back({p, {"random", int(sc.commands.size()) + 1}});
  }
  return sc;
}

nlohmann::json stats_without_time(const RenderStats& s) {
  nlohmann::json j = to_json(s);
  j.erase("wall_seconds");
  return j;
}

struct Case {
  std::string config;
  int samples;
  AaMode mode;
};

class ThreadsTest : public ::testing::TestWithParam<Case> {};

TEST_P(ThreadsTest, SameImageCrcAndStatsAsOneThread) {
  const Case c = GetParam();
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + c.config + ".toml");
  const uint32_t seed = 20261124u + uint32_t(c.samples) * 7u + uint32_t(c.mode) + uint32_t(c.config.size());
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (const Traversal method : {Traversal::Tiled, Traversal::Bbox, Traversal::Hierarchical}) {
    RasterState st = raster_state_from_config(cfg);
    st.samples = c.samples;
    st.aa_mode = c.mode;
    st.traversal = method;
    if (st.hier_levels.empty()) st.hier_levels = {64, 16, 4};
    st.out_of_range = OutOfRange::Cull;
    st.depth_func = DepthFunc::LEqual;  // the order of a pixel's fragments decides its colour
    st.depth_write = true;
    const Scene scene = random_scene(rng, st.fb_width, st.fb_height);
    SCOPED_TRACE(std::string("traversal ") + to_string(method));
    RenderStats one, many;
    const Framebuffer a = render_scene(scene, st, one, {}, Framebuffer::kDefaultTileLog2, 1);
    const Framebuffer b = render_scene(scene, st, many, {}, Framebuffer::kDefaultTileLog2, 3);
    EXPECT_TRUE(a.same_color(b));
    EXPECT_TRUE(a.same_depth(b));
    EXPECT_EQ(one.framebuffer_crc32, many.framebuffer_crc32);
    EXPECT_EQ(stats_without_time(one), stats_without_time(many));
    EXPECT_GT(one.traversal.fragments, 10000u);  // the scene draws something
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, ThreadsTest,
                         ::testing::Values(Case{"default", 1, AaMode::Msaa}, Case{"d3d11", 1, AaMode::Msaa},
                                           Case{"desktop", 1, AaMode::Msaa}, Case{"embedded", 1, AaMode::Msaa},
                                           Case{"default", 4, AaMode::Msaa}, Case{"d3d11", 4, AaMode::Ssaa},
                                           Case{"desktop", 8, AaMode::Msaa}),
                         [](const auto& info) {
                           return info.param.config + "S" + std::to_string(info.param.samples) +
                                  (info.param.mode == AaMode::Ssaa ? "ssaa" : "msaa");
                         });

// A fragment sink needs the pipeline order and scanline's coverage check is per triangle:
// both keep one thread.
TEST(Threads, FragmentSinkAndScanlineKeepOneThread) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml");
  RasterState st = raster_state_from_config(cfg);
  RenderStats s;
  EXPECT_EQ(SceneRenderer(st, s, {}, Framebuffer::kDefaultTileLog2, 4).threads(), 4);
  EXPECT_EQ(SceneRenderer(st, s, [](const Fragment&) {}, Framebuffer::kDefaultTileLog2, 4).threads(), 1);
  st.traversal = Traversal::Scanline;
  EXPECT_EQ(SceneRenderer(st, s, {}, Framebuffer::kDefaultTileLog2, 4).threads(), 1);
}

}  // namespace
}  // namespace rastsim
