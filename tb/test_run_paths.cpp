// SPDX-License-Identifier: Apache-2.0
// The reference pipeline's run path (pipeline.cpp draw(): traversal hands runs of covered
// pixels to the shader and to rop_write_run) against the per-pixel path it replaces:
// - rop_write_run against rop_write on each fragment in turn, on framebuffers with some
//   tiles stored and some not, small storage tiles (runs cross them), every depth
//   function, with and without depth writes: the same colour, depth, tile allocations and
//   counts;
// - whole random scenes (flat-shaded triangles, whose PlaneStepper divides nothing, mixed
//   with smoothly shaded ones; every depth function) drawn with a fragment sink, which
//   keeps the per-pixel path, and without: the same framebuffer, CRC and stats, and as
//   many fragments as the sink saw.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "common/random_vertex.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/rop.h"
#include "ref/traverse.h"
#include "report/stats_json.h"

namespace rastsim {
namespace {

constexpr DepthFunc kFuncs[] = {DepthFunc::Never,   DepthFunc::Less,   DepthFunc::LEqual,   DepthFunc::Equal,
                                DepthFunc::Greater, DepthFunc::GEqual, DepthFunc::NotEqual, DepthFunc::Always};

TEST(RopRun, SameWritesAsRopWriteOnEachFragment) {
  const uint32_t seed = 0x7075u;
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::uniform_int_distribution<int> pct(0, 99), byte(0, 255);
  for (int tile_log2 : {2, 3, 5}) {
    const int W = 70, H = 20;
    Framebuffer run(W, H, 1, tile_log2), each(W, H, 1, tile_log2);
    for (Framebuffer* fb : {&run, &each}) {
      fb->clear_depth(4);
      fb->clear_color(1, 2, 3);
    }
    for (int op = 0; op < 3000; ++op) {
      const DepthFunc func = kFuncs[size_t(pct(rng)) % 8];
      const bool depth_write = pct(rng) < 70;
      const int y = std::uniform_int_distribution<int>(0, H - 1)(rng);
      const int x0 = std::uniform_int_distribution<int>(0, W - 1)(rng);
      const int x1 = std::min(W, x0 + std::uniform_int_distribution<int>(1, 40)(rng));
      std::vector<Fragment> frags;
      for (int x = x0; x < x1; ++x) {
        Fragment f;
        f.x = x, f.y = y, f.z = uint32_t(byte(rng) % 9), f.r = uint8_t(byte(rng)), f.g = uint8_t(op);
        f.b = uint8_t(x);
        frags.push_back(f);
      }
      uint32_t written = 0;
      for (const Fragment& f : frags) written += rop_write(each, f, func, depth_write) ? 1 : 0;
      const uint32_t n = rop_write_run(
          run, y, x0, x1, [&](int x) { return frags[size_t(x - x0)]; }, func, depth_write);
      ASSERT_EQ(n, written) << "op " << op;
      ASSERT_EQ(run.color_tiles_allocated(), each.color_tiles_allocated()) << "op " << op;
      ASSERT_EQ(run.depth_tiles_allocated(), each.depth_tiles_allocated()) << "op " << op;
      if (op % 500 == 499) {  // a clear now and then: runs over tiles not stored again
        const uint32_t z = uint32_t(byte(rng) % 9);
        run.clear_depth(z), each.clear_depth(z);
      }
    }
    EXPECT_TRUE(run.same_color(each)) << "tile_log2 " << tile_log2;
    EXPECT_TRUE(run.same_depth(each)) << "tile_log2 " << tile_log2;
    EXPECT_EQ(run.color_crc32(), each.color_crc32());
  }
}

// Triangles of 1..60 px around the screen, a third flat-shaded (one colour and depth),
// a third with some attributes flat, the rest smooth.
Scene random_scene(std::mt19937& rng, int w, int h, int n) {
  Scene sc;
  sc.source = "random";
  std::uniform_int_distribution<int> pct(0, 99);
  std::uniform_real_distribution<double> cx(-20, w + 20), cy(-20, h + 20);
  CmdPrimitives p;
  for (int t = 0; t < n; ++t) {
    const double x = cx(rng), y = cy(rng), r = std::uniform_real_distribution<double>(0.5, 30)(rng);
    const int kind = pct(rng) % 3;
    const int flat_mask = kind == 0 ? 15 : kind == 1 ? std::uniform_int_distribution<int>(1, 14)(rng) : 0;
    SceneVertex first;
    for (int v = 0; v < 3; ++v) {
      SceneVertex sv = test::random_vertex_on_circle(rng, x, y, r);
      if (v == 0) first = sv;
      if (flat_mask & 1) sv.z = first.z;
      if (flat_mask & 2) sv.r = first.r;
      if (flat_mask & 4) sv.g = first.g;
      if (flat_mask & 8) sv.b = first.b;
      p.vertices.push_back(sv);
    }
  }
  sc.commands.push_back({CmdClear{9, 8, 7}, {"random", 1}});
  sc.commands.push_back({p, {"random", 2}});
  return sc;
}

nlohmann::json stats_without_time(const RenderStats& s) {
  nlohmann::json j = to_json(s);
  j.erase("wall_seconds");
  return j;
}

class RunPath : public ::testing::TestWithParam<std::string> {};

TEST_P(RunPath, SameImageAndStatsAsThePerPixelPath) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + GetParam() + ".toml");
  const uint32_t seed = 20261124u + uint32_t(GetParam().size());
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (const DepthFunc func : kFuncs) {
    for (const Traversal method : {Traversal::Tiled, Traversal::Bbox, Traversal::Hierarchical}) {
      RasterState st = raster_state_from_config(cfg);
      st.samples = 1;
      st.interp_method = InterpMethod::Plane;
      st.traversal = method;
      if (st.hier_levels.empty()) st.hier_levels = {64, 16, 4};
      st.out_of_range = OutOfRange::Cull;
      st.depth_func = func;
      st.depth_write = rng() % 4 != 0;
      SCOPED_TRACE(std::string("traversal ") + to_string(method) + ", depth func " +
                   std::to_string(int(func)));
      const Scene scene = random_scene(rng, st.fb_width, st.fb_height, 400);
      RenderStats runs, pixels;
      uint64_t sunk = 0;
      const Framebuffer a = render_scene(scene, st, runs);
      const Framebuffer b = render_scene(scene, st, pixels, [&](const Fragment&) { ++sunk; });
      EXPECT_TRUE(a.same_color(b));
      EXPECT_TRUE(a.same_depth(b));
      EXPECT_EQ(runs.framebuffer_crc32, pixels.framebuffer_crc32);
      EXPECT_EQ(stats_without_time(runs), stats_without_time(pixels));
      EXPECT_EQ(runs.fragments_shaded, sunk);
      EXPECT_GT(sunk, 2000u);  // the scene draws something
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, RunPath, ::testing::Values("default", "d3d11", "desktop", "embedded"));

}  // namespace
}  // namespace rastsim
