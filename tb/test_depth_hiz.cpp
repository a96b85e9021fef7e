// SPDX-License-Identifier: Apache-2.0
// depth.hiz (docs/depth-culling.md): hierarchical Z changes no image and no depth write.
// Checked on a hand-worked corner bound, on thousands of seeded random triangles over the
// four shipped configs and every mode and block size (CRCs against Hi-Z off and early Z
// off; every culled and accepted tile checked by brute force against the framebuffer as
// the ROP would test it), and the oracle score on layered scenes drawn front to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/fine_raster.h"
#include "ref/hiz.h"
#include "ref/pipeline.h"
#include "scene_test.h"
#include "ref/rop.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

using scene_test::screen_vertex;
SceneVertex vertex(double x, double y, double z, uint8_t r) { return screen_vertex(x, y, z, r); }

// The corner bound by hand: a 16 x 16 viewport (s7.16, origin at pixel (8, 8)), the
// triangle A (0, 0) z 1, B (16, 0) z 0, C (0, 16) z 0 (pixel-edge coordinates; z 1 is
// 2^24 - 1 = 16777215 in 24 bits), so z(x, y) = 16777215 (1 - x/16 - y/16). Tile
// [0, 8) x [0, 8): its corner pixel centres are (0.5, 0.5), nearest-to-A, z =
// 16777215 x 15/16 = 15728639.0625, and (7.5, 7.5), z = 16777215 x 1/16 = 1048575.9375
// (the other two corners give 16777215 x 1/2 = 8388607.5). The range is rounded away
// from the fragments: lo = floor(1048575.9375) = 1048575, hi = ceil(15728639.0625) =
// 15728640. The fragments there, rounded half up: pixel (7, 7) 1048576, pixel (0, 0)
// 15728639, both inside [lo, hi] and each one LSB from its end.
TEST(DepthHiz, CornerBoundHandWorked) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = st.viewport_width = st.viewport_height = 16;
  SetupTriangle t;
  const std::array<SceneVertex, 3> v{vertex(0, 0, 1.0, 0), vertex(16, 0, 0.0, 0), vertex(0, 16, 0.0, 0)};
  ASSERT_EQ(setup_triangle(v, st, {"hand", 1}, t), SetupOutcome::Accepted);
  const int F = st.coord_format.frac_bits;
  const DepthRange r = tile_depth_range(t, {0, 0, 8, 8}, F);
  EXPECT_EQ(r.lo, 1048575);
  EXPECT_EQ(r.hi, 15728640);
  EXPECT_EQ(interpolate_plane(t, 7, 7, F).z, 1048576u);
  EXPECT_EQ(interpolate_plane(t, 0, 0, F).z, 15728639u);
  // A tile whose corners lie outside the triangle: the bound is clamped to the vertices'.
  const DepthRange far = tile_depth_range(t, {8, 8, 16, 16}, F);
  EXPECT_EQ(far.lo, 0);  // the plane goes negative at (15.5, 15.5): clamped to min z_k = 0
  // Its nearest corner (8.5, 8.5) is past the far edge too: 16777215 (1 - 17/16) =
  // -1048575.9375, ceil -1048575, clamped to -1 (was cast to uint32: 4293918721, a bound
  // above every stored depth); below every stored bound either way an exact test says.
  EXPECT_EQ(far.hi, -1);
}

// The spilled table's bytes by hand: a 16 x 16 screen, 8 px blocks (4 blocks, row-major
// 0 1 / 2 3), max mode, 24-bit depth: an entry is 2 x 24 + 64 = 112 bits -> 14 -> 16
// bytes; depth.hiz_bytes = 32 keeps blocks 0 and 1 on chip, 2 and 3 spilled. One 16 px
// tile. The quad [0, 16) x [8, 16) at z 0.5 (two triangles, each with pixels in blocks 2
// and 3): each triangle's tile test reads entries 2 and 3 (32 bytes) and its flush reads
// and writes both (32 + 32); the second triangle completes both blocks' layers, so their
// max falls to 0.5. The same quad at z 0.7: both triangles' tiles are culled (32 bytes
// read each, no write), 2 x 64 = 128 fragments. Read 2 x 64 + 64 = 192, written 64.
TEST(DepthHiz, SpilledTableBytesHandCounted) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = 16;
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  st.hiz_mode = HizMode::Max;
  st.hiz_block = 8;
  st.hiz_bytes = 32;
  const auto quad = [](double z) {
    CmdPrimitives p;
    p.vertices = {vertex(0, 8, z, 9), vertex(16, 8, z, 9), vertex(0, 16, z, 9),
                  vertex(16, 8, z, 9), vertex(16, 16, z, 9), vertex(0, 16, z, 9)};
    return p;
  };
  Scene scene;
  scene.commands.push_back({CmdViewport{16, 16}, {"hand", 1}});
  scene.commands.push_back({quad(0.5), {"hand", 2}});
  scene.commands.push_back({quad(0.7), {"hand", 3}});
  RenderStats s;
  render_scene(scene, st, s);
  EXPECT_EQ(HizTable(HizMode::Max, 8, 32, 16, 16, 24).entry_bytes(), 16);
  EXPECT_EQ(HizTable(HizMode::MinMax, 16, 0, 16, 16, 24).entry_bytes(), 64);  // 4 x 24 + 256 = 352 bits -> 44 -> 64
  EXPECT_EQ(s.hiz.tiles_tested, 4u);
  EXPECT_EQ(s.hiz.tiles_culled, 2u);
  EXPECT_EQ(s.hiz.fragments_culled, 128u);
  EXPECT_EQ(s.hiz.layer_completions, 2u);
  EXPECT_EQ(s.hiz.bytes_read, 192u);
  EXPECT_EQ(s.hiz.bytes_written, 64u);
  EXPECT_EQ(s.fragments_passed, 128u);
  EXPECT_EQ(hiz_culled_fraction(s), 1.0);  // every failing fragment was culled
}

// Every Hi-Z decision checked by brute force when coarse raster makes it: each covered
// pixel of the footprint interpolated exactly and tested against the stored depth as the
// ROP would. A culled tile must hold no passing fragment, an accepted one no failing one.
struct BruteForce {
  uint64_t culled = 0, accepted = 0, wrong = 0;
  void operator()(const HizEvent& e) {
    const int F = frac_bits;
    for (int y = e.footprint.y0; y < e.footprint.y1; ++y)
      for (int x = e.footprint.x0; x < e.footprint.x1; ++x) {
        if (!pixel_covered(e.tri, x, y, F)) continue;
        const bool pass = depth_test(e.func, interpolate_plane(e.tri, x, y, F).z, e.fb.depth_at(x, y, 0));
        wrong += e.decision == HizDecision::Culled ? pass : !pass;
      }
    (e.decision == HizDecision::Culled ? culled : accepted) += 1;
  }
  int frac_bits = 16;
};

struct HizRun {
  RenderStats stats;
  BruteForce check;
};

HizRun render(const Scene& scene, const RasterState& st) {
  HizRun r;
  r.check.frac_bits = st.coord_format.frac_bits;
  SceneRenderer renderer(st, r.stats);
  renderer.set_hiz_observer([&](const HizEvent& e) { r.check(e); });
  renderer.run(scene.commands);
  renderer.finish();
  return r;
}

// n random triangles over a w x h screen, a depth clear in the middle half the time.
Scene random_scene(std::mt19937& rng, int w, int h, int n) {
  std::uniform_real_distribution<double> xs(-0.2 * w, 1.2 * w), ys(-0.2 * h, 1.2 * h), z(0, 1);
  std::uniform_int_distribution<int> c(0, 255);
  Scene scene;
  scene.commands.push_back({CmdViewport{w, h}, {"random", 1}});
  CmdPrimitives a, b;
  for (int k = 0; k < n; ++k)
    for (int v = 0; v < 3; ++v) (k < n / 2 ? a : b).vertices.push_back(vertex(xs(rng), ys(rng), z(rng), uint8_t(c(rng))));
  scene.commands.push_back({a, {"random", 2}});
  if (rng() % 2) scene.commands.push_back({CmdClearDepth{z(rng)}, {"random", 3}});
  scene.commands.push_back({b, {"random", 4}});
  return scene;
}

std::vector<std::string> shipped_configs() {
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(fs::path(RASTSIM_SOURCE_DIR) / "configs"))
    if (e.is_regular_file() && e.path().extension() == ".toml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// Random triangles over the four shipped configs (their coordinate formats, tile sizes,
// depth widths), each mode and block size, the four depth functions Hi-Z handles, depth
// writes on and off, early Z off and on, the table on chip and spilled: the image, the
// passed fragments and the depth writes equal Hi-Z off's; no decision is wrong.
TEST(DepthHiz, RandomTrianglesSameImageAndConservative) {
  const std::vector<std::string> configs = shipped_configs();
  ASSERT_EQ(configs.size(), 4u);
  std::mt19937 rng(2929);
  uint64_t triangles = 0, culled = 0, accepted = 0, wrong = 0, spilled_bytes = 0;
  for (const std::string& path : configs) {
    Config cfg;
    cfg.load_file(path);
    cfg.apply_override("display.width=48");
    cfg.apply_override("display.height=40");  // not a multiple of 16: partial edge blocks
    const RasterState base = raster_state_from_config(cfg);
    for (HizMode mode : {HizMode::Max, HizMode::MinMax})
      for (int block : {4, 8, 16})
        for (DepthFunc func : {DepthFunc::Less, DepthFunc::LEqual, DepthFunc::Greater, DepthFunc::GEqual}) {
          const Scene scene = random_scene(rng, 48, 40, 40);
          RasterState st = base;
          st.depth_func = func;
          st.depth_write = rng() % 4 != 0;
          st.depth_early = rng() % 2;
          RasterState off = st;
          off.hiz_mode = HizMode::Off;
          off.depth_early = false;
          st.hiz_mode = mode;
          st.hiz_block = block;
          st.hiz_bytes = rng() % 2 ? (int64_t{1} << 20) : 64;  // all on chip, or most spilled
          SCOPED_TRACE(path + " mode " + std::to_string(int(mode)) + " block " + std::to_string(block) + " func " +
                       to_string(func));
          const HizRun h = render(scene, st), o = render(scene, off);
          EXPECT_EQ(h.stats.framebuffer_crc32, o.stats.framebuffer_crc32);
          EXPECT_EQ(h.stats.fragments_passed, o.stats.fragments_passed);
          EXPECT_EQ(h.stats.depth_writes, o.stats.depth_writes);
          // Every fragment the late test fails is culled by one of the three, or tested.
          EXPECT_EQ(h.stats.fragments_shaded + h.stats.fragments_culled_early + h.stats.hiz.fragments_culled,
                    o.stats.fragments_shaded);
          EXPECT_EQ(h.check.culled, h.stats.hiz.tiles_culled);
          EXPECT_EQ(h.check.accepted, h.stats.hiz.tiles_accepted);
          triangles += 40;
          culled += h.check.culled;
          accepted += h.check.accepted;
          wrong += h.check.wrong;
          spilled_bytes += h.stats.hiz.bytes_read;
        }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GE(triangles, 3000u);
  EXPECT_GT(culled, 100u);  // the scenes exercise every decision
  EXPECT_GT(accepted, 20u);
  EXPECT_GT(spilled_bytes, 0u);
  std::printf("hiz random: %llu triangles, %llu tiles culled, %llu accepted, 0 wrong\n",
              (unsigned long long)triangles, (unsigned long long)culled, (unsigned long long)accepted);
}

// d overlapping layers over w x h, layer k (0 nearest) drawn in `order`: the last a
// full-screen background, the others random rectangles of a quarter to the whole screen
// a side. Each is a grid of 4 x 4 px quads (two triangles each) whose depth slopes by 0.05
// across the screen from 0.1 + 0.1 k, so layers never interpenetrate and no block's
// bound is exact.
Scene layered_scene(int w, int h, const std::vector<int>& order, std::mt19937& rng) {
  Scene scene;
  scene.commands.push_back({CmdViewport{w, h}, {"layers", 1}});
  const int d = int(order.size());
  std::vector<std::array<int, 4>> rects(order.size());
  for (int k = 0; k < d; ++k) {
    std::uniform_int_distribution<int> sw(w / 4, w), sh(h / 4, h);
    const int rw = k == d - 1 ? w : sw(rng), rh = k == d - 1 ? h : sh(rng);
    const int x0 = std::uniform_int_distribution<int>(0, w - rw)(rng), y0 = std::uniform_int_distribution<int>(0, h - rh)(rng);
    rects[size_t(k)] = {x0, y0, x0 + rw, y0 + rh};
  }
  for (int layer : order) {
    const auto [rx0, ry0, rx1, ry1] = rects[size_t(layer)];
    const auto z = [&](double x, double y) { return 0.1 + 0.1 * layer + 0.05 * (x + y) / double(w + h); };
    CmdPrimitives p;
    for (int y = ry0; y < ry1; y += 4)
      for (int x = rx0; x < rx1; x += 4) {
        const double x0 = x, y0 = y, x1 = std::min(x + 4, rx1), y1 = std::min(y + 4, ry1);
        const uint8_t c = uint8_t(30 * layer + 7);
        for (const auto& [px, py] : {std::pair{x0, y0}, {x1, y0}, {x0, y1}, {x1, y0}, {x1, y1}, {x0, y1}})
          p.vertices.push_back(vertex(px, py, z(px, py), c));
      }
    scene.commands.push_back({p, {"layers", 2 + layer}});
  }
  return scene;
}

// The oracle score on 8 overlapping layers (64 x 64, less, minmax), the same layers drawn
// front to back and in a random order, for every block size and tiles of 8 and 16 px.
// Early Z off: every fragment behind a nearer layer fails the late test, and Hi-Z alone
// removes those in tiles whose blocks are bounded (a block's max falls once the layers
// drawn so far have written every pixel of it). With 4 px blocks and 8 px tiles it must
// remove at least 90 % of them front to back; the rest are printed (docs/depth-culling.md).
// Early Z on: the reference's early test is exact, so the score is 1.
TEST(DepthHiz, OracleScoreFrontToBack) {
  std::mt19937 rng(29);
  std::vector<int> order(8);
  for (int k = 0; k < 8; ++k) order[size_t(k)] = k;
  std::mt19937 layers(rng()), again = layers;  // the same rectangles in both orders
  const Scene f2b_scene = layered_scene(64, 64, order, layers);
  std::shuffle(order.begin(), order.end(), rng);
  const Scene rnd_scene = layered_scene(64, 64, order, again);
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = 64;
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  st.hiz_mode = HizMode::MinMax;
  st.hiz_bytes = 1 << 20;
  for (int block : {4, 8, 16})
    for (int tile : {8, 16}) {
      st.hiz_block = block;
      st.tile_size = tile;
      st.depth_early = false;
      const HizRun f2b = render(f2b_scene, st), rnd = render(rnd_scene, st);
      std::printf("oracle, block %2d, tile %2d: Hi-Z alone front to back %.4f (%llu tiles culled), random order %.4f\n",
                  block, tile, hiz_culled_fraction(f2b.stats), (unsigned long long)f2b.stats.hiz.tiles_culled,
                  hiz_culled_fraction(rnd.stats));
      EXPECT_EQ(f2b.check.wrong + rnd.check.wrong, 0u);
      // Front to back each pixel is written once, by the nearest layer over it (the fill
      // rule owns each pixel once within a layer; the last layer covers the screen).
      EXPECT_EQ(f2b.stats.fragments_passed, 4096u);
      EXPECT_EQ(hiz_oracle_fraction(f2b.stats), hiz_culled_fraction(f2b.stats));  // early Z off
      if (block == 4 && tile == 8) {
        EXPECT_GE(hiz_culled_fraction(f2b.stats), 0.90);
      }
      st.depth_early = true;
      const HizRun f2b_early = render(f2b_scene, st), rnd_early = render(rnd_scene, st);
      EXPECT_EQ(hiz_oracle_fraction(f2b_early.stats), 1.0);
      EXPECT_EQ(hiz_oracle_fraction(rnd_early.stats), 1.0);
    }
}

}  // namespace
}  // namespace rastsim
