// SPDX-License-Identifier: Apache-2.0
// pipeline.mode = binned (ref/binning.h, docs/binning.md): the parameter buffer's bytes
// on a hand-worked scene (with and without overflow, bbox and exact), exact binning
// against a brute-force coverage test of every pixel of every bin, and images identical
// (CRC) to immediate mode on random scenes and the shipped scenes under the 4 configs,
// for every bin size 8 .. 128, both rules, overflow, and 1 and 4 samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/obj_placement.h"
#include "common/screen_vertex.h"
#include "config/memory_config.h"
#include "config/raster_state_config.h"
#include "ref/fine_raster.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

CmdPrimitives triangle(SceneVertex a, SceneVertex b, SceneVertex c) {
  CmdPrimitives p;
  p.vertices = {a, b, c};
  return p;
}

RasterState binned(RasterState st, int w, int h, BinningRule rule, uint64_t pb_bytes) {
  st.bin.mode = PipelineMode::Binned;
  st.bin.width = w;
  st.bin.height = h;
  st.bin.rule = rule;
  st.bin.parameter_buffer_bytes = pb_bytes;
  return st;
}

RenderStats render(const Scene& scene, const RasterState& st) {
  RenderStats s;
  render_scene(scene, st, s);
  return s;
}

// 64 x 64 screen, 32 x 32 bins (4: 0 1 / 2 3), depth 24 bits (4 bytes a sample):
// a colour clear, D = (2,2) (62,2) (2,62) (box over every bin; its hypotenuse x + y = 64
// leaves bin 3's pixel centres, x + y >= 65, uncovered) and A = (2,2) (20,2) (2,20) (bin 0).
Scene hand_scene() {
  Scene scene;
  scene.commands.push_back({CmdViewport{64, 64}, {"hand", 1}});
  scene.commands.push_back({CmdClear{10, 20, 30}, {"hand", 2}});
  const auto tri = [](double x1, double y2, double z, uint8_t r) {
    return triangle(screen_vertex(2, 2, z, r), screen_vertex(x1, 2, z, r), screen_vertex(2, y2, z, r));
  };
  scene.commands.push_back({tri(62, 62, 0.5, 200), {"hand", 3}});  // D
  scene.commands.push_back({tri(20, 20, 0.2, 90), {"hand", 4}});   // A
  return scene;
}

RasterState hand_state() {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = 64;
  st.depth_bits = 24;
  st.cull = CullMode::None;
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  return st;
}

// Bytes by hand (triangle records 64, clear records 16, list entries 4; colour 4, depth
// 4 bytes a sample): bbox: written clear 16, D 64 + 4 x 4, A 64 + 4 = 16 + 80 + 68 = 164;
// read per bin (every bin reads the clear; its entries and their records): bin 0 16 +
// 2 x (4 + 64) = 152, bins 1..3 16 + 4 + 64 = 84 each: 404; geometry 568. exact: D in
// bins 0..2 only: written 16 + 76 + 68 = 160, read 152 + 84 + 84 + 16 = 336; geometry
// 496. Framebuffer: 4 bins x 1024 px x 4 bytes of colour stored, nothing loaded: 16384.
TEST(Binning, HandWorkedBytes) {
  const Scene scene = hand_scene();
  const RasterState st = hand_state();
  const RenderStats imm = render(scene, st);
  for (BinningRule rule : {BinningRule::Bbox, BinningRule::Exact}) {
    const bool exact = rule == BinningRule::Exact;
    SCOPED_TRACE(exact ? "exact" : "bbox");
    const RenderStats b = render(scene, binned(st, 32, 32, rule, 1 << 20));
    EXPECT_EQ(b.framebuffer_crc32, imm.framebuffer_crc32);
    EXPECT_EQ(b.bin.bins, 4u);
    EXPECT_EQ(b.bin.geometry_bytes_written, exact ? 160u : 164u);
    EXPECT_EQ(b.bin.geometry_bytes_read, exact ? 336u : 404u);
    EXPECT_EQ(b.bin.dram_bytes_geometry(), exact ? 496u : 568u);
    EXPECT_EQ(b.bin.framebuffer_bytes_read, 0u);
    EXPECT_EQ(b.bin.dram_bytes_framebuffer(), 16384u);
    EXPECT_DOUBLE_EQ(b.bin.primitives_per_bin_mean(), exact ? 1.0 : 1.25);
    EXPECT_EQ(b.bin.bin_overflows, 0u);
    EXPECT_EQ(b.fragments_passed, imm.fragments_passed);
  }
  // Every load and store flag on: each bin also reads colour and depth (8192) and
  // stores depth (4096): 4 x 8192 read, 4 x 8192 written.
  RasterState all = binned(st, 32, 32, BinningRule::Bbox, 1 << 20);
  all.bin.load_color = all.bin.load_depth = all.bin.store_depth = true;
  const RenderStats f = render(scene, all);
  EXPECT_EQ(f.framebuffer_crc32, imm.framebuffer_crc32);
  EXPECT_EQ(f.bin.framebuffer_bytes_read, 32768u);
  EXPECT_EQ(f.bin.framebuffer_bytes_written, 32768u);
}

// A 120-byte parameter buffer (bbox): clear (16) and D (80) fill 96, A (68) does not
// fit: an overflow pass renders all 4 bins, storing colour and depth (4 x 8192); then A
// alone: bin 0 reloads colour and depth (8192) and stores its colour (4096); bins 1..3,
// stored already and with empty lists, are not rendered again. Framebuffer 32768 + 8192
// + 4096 = 45056; geometry as without overflow (every record and entry written and read
// as often): 568.
TEST(Binning, HandWorkedOverflow) {
  const Scene scene = hand_scene();
  const RasterState st = hand_state();
  const RenderStats b = render(scene, binned(st, 32, 32, BinningRule::Bbox, 120));
  EXPECT_EQ(b.framebuffer_crc32, render(scene, st).framebuffer_crc32);
  EXPECT_EQ(b.bin.bin_overflows, 1u);
  EXPECT_EQ(b.bin.bins_rendered, 5u);
  EXPECT_EQ(b.bin.framebuffer_bytes_written, 32768u + 4096u);
  EXPECT_EQ(b.bin.framebuffer_bytes_read, 8192u);
  EXPECT_EQ(b.bin.dram_bytes_framebuffer(), 45056u);
  EXPECT_EQ(b.bin.dram_bytes_geometry(), 568u);
  // A buffer smaller than one record and its entries is a clear error naming the command:
  // 64 bytes take the clear (16), not D (80).
  try {
    render(scene, binned(st, 32, 32, BinningRule::Bbox, 64));
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("hand:3"), std::string::npos) << e.what();
  }
}

// Random triangles (some off screen, some thin): the bins exact binning lists are
// exactly those where a brute-force test of every pixel's samples finds coverage.
TEST(Binning, ExactListsOnlyCoveredBins) {
  std::mt19937 rng(290029);
  std::uniform_real_distribution<double> xy(-20, 120);
  uint64_t fewer = 0;
  for (int samples : {1, 4}) {
    RasterState st = raster_state_from_config(Config{});
    st.fb_width = 100;
    st.fb_height = 70;
    st.viewport_width = 100;
    st.viewport_height = 70;
    st.samples = samples;
    for (auto [w, h] : {std::pair{8, 8}, {16, 32}, {32, 8}, {64, 64}}) {
      RasterState ex = binned(st, w, h, BinningRule::Exact, 1 << 20), bb = binned(st, w, h, BinningRule::Bbox, 1 << 20);
      Framebuffer fb(st.fb_width, st.fb_height, samples);
      RenderStats stats;
      Binner exact(ex, traversal_params(ex), fb, [](const SetupTriangle&, const SetupTriangle&) {}, stats.bin);
      Binner box(bb, traversal_params(bb), fb, [](const SetupTriangle&, const SetupTriangle&) {}, stats.bin);
      for (int n = 0; n < 300; ++n) {
        ScreenTriangle v;
        for (auto& p : v) p = screen_vertex(xy(rng), xy(rng), 0.5, 1);
        SetupTriangle tri;
        if (setup_triangle(v, st, {"random", n}, tri) != SetupOutcome::Accepted) continue;
        std::set<int> covered;
        for (int b = 0; b < exact.bins_x() * exact.bins_y(); ++b) {
          const PixelRect r = exact.bin_rect(b);
          for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x)
              if (pixel_sample_mask(tri, x, y, st.coord_format.frac_bits)) covered.insert(b);
        }
        const std::vector<int> listed = exact.bins_of(tri), boxed = box.bins_of(tri);
        EXPECT_EQ(std::set<int>(listed.begin(), listed.end()), covered) << "triangle " << n;
        EXPECT_TRUE(std::includes(boxed.begin(), boxed.end(), listed.begin(), listed.end()));
        fewer += boxed.size() - listed.size();
      }
    }
  }
  EXPECT_GT(fewer, 0u);  // the scenes have boxes over bins they do not cover
}

// A random scene: `n` triangles at random depths and colours in batches, with a colour
// and depth clear and a scissor change between batches.
Scene random_scene(std::mt19937& rng, int W, int H, int n) {
  std::uniform_real_distribution<double> x(-10, W + 10), y(-10, H + 10), z(0, 1);
  std::uniform_int_distribution<int> c(0, 255);
  Scene scene;
  scene.commands.push_back({CmdViewport{W, H}, {"random", 1}});
  for (int batch = 0; batch < 4; ++batch) {
    if (batch == 2) scene.commands.push_back({CmdClear{uint8_t(c(rng)), 7, 9}, {"random", 2}});
    if (batch == 2) scene.commands.push_back({CmdClearDepth{0.7}, {"random", 3}});
    if (batch == 1) scene.commands.push_back({CmdScissor{true, 13, 9, W / 2, H / 2}, {"random", 4}});
    if (batch == 3) scene.commands.push_back({CmdScissor{false, 0, 0, 0, 0}, {"random", 5}});
    CmdPrimitives p;
    for (int v = 0; v < 3 * n / 4; ++v)
      p.vertices.push_back(screen_vertex(x(rng), y(rng), z(rng), uint8_t(c(rng)), uint8_t(c(rng))));
    scene.commands.push_back({p, {"random", 10 + batch}});
  }
  return scene;
}

// Every bin size 8 .. 128 (squares and two oblong), bbox and exact, with a parameter
// buffer that holds every record and one that overflows many times, 1 and 4 samples,
// over seeded random scenes of 300 triangles on a 200 x 150 screen (not a whole number
// of bins), traversal tiled, hierarchical and bbox (one a seed, one a test instance, so
// that scripts/test's sanitizer run can take the hierarchical one alone: docs/ci.md): the
// CRC equals immediate mode's.
class BinningRandom : public ::testing::TestWithParam<int> {};

TEST_P(BinningRandom, ScenesSameImage) {
  const int seed = GetParam();
  std::mt19937 rng(29);
  Scene scene;
  for (int s = 0; s <= seed; ++s) scene = random_scene(rng, 200, 150, 300);  // the seed's scene of one stream
  uint64_t overflows = 0;
  for (int samples : {1, 4}) {
    RasterState st = raster_state_from_config(Config{});
    st.fb_width = 200;
    st.fb_height = 150;
    st.samples = samples;
    st.depth_func = DepthFunc(2 + seed);  // lequal, equal, greater
    st.depth_write = true;
    st.traversal = std::array{Traversal::Tiled, Traversal::Hierarchical, Traversal::Bbox}[size_t(seed)];
    const RenderStats imm = render(scene, st);
    for (auto [w, h] : {std::pair{8, 8}, {16, 16}, {32, 32}, {64, 64}, {128, 128}, {8, 128}, {64, 16}})
      for (BinningRule rule : {BinningRule::Bbox, BinningRule::Exact})
        for (uint64_t pb : {uint64_t{1} << 24, uint64_t{4096}}) {
          SCOPED_TRACE("samples " + std::to_string(samples) + " bin " + std::to_string(w) + "x" + std::to_string(h) +
                       (rule == BinningRule::Exact ? " exact" : " bbox") + " pb " + std::to_string(pb));
          const RenderStats b = render(scene, binned(st, w, h, rule, pb));
          EXPECT_EQ(b.framebuffer_crc32, imm.framebuffer_crc32);
          EXPECT_EQ(b.fragments_passed, imm.fragments_passed);
          EXPECT_EQ(b.depth_writes, imm.depth_writes);
          if (pb == 4096) {
            EXPECT_GT(b.bin.bin_overflows, 0u);
          }
          overflows += b.bin.bin_overflows;
        }
  }
  EXPECT_GT(overflows, 0u);
}

INSTANTIATE_TEST_SUITE_P(Traversals, BinningRandom, ::testing::Values(0, 1, 2), [](const auto& info) {
  return std::string(std::array{"tiled", "hierarchical", "bbox"}[size_t(info.param)]);
});

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> paths;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(RASTSIM_SOURCE_DIR) / "traces"))
    if (e.is_regular_file() && e.path().extension() == ".trace") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  paths.push_back((fs::path(RASTSIM_SOURCE_DIR) / "tb" / "data" / "cube.obj").string());
  return paths;
}

uint64_t bin_count(const RasterState& st, int size) {
  return uint64_t((st.fb_width + size - 1) / size) * uint64_t((st.fb_height + size - 1) / size);
}

bool binned_draws(const Scene& scene, const RasterState& st) {
  try {
    for (const Command& c : scene.commands) check_binned_command(c, st);
  } catch (const SceneError&) {
    return false;
  }
  return true;
}

// The shipped scenes (traces/, the OBJ cube) under the 4 shipped configs, bins 8, 32 and
// 128, bbox and exact, with and without overflow: the CRC equals immediate mode's. The
// scenes binned mode refuses (2D drawing, homogeneous clipping) must be refused by name.
TEST(Binning, ShippedScenesAndConfigsSameImage) {
  int compared = 0;
  uint64_t overflows = 0;
  for (const char* config : {"default", "d3d11", "desktop", "embedded"}) {
    Config cfg;
    cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + config + ".toml");
    cfg.apply_override("bin.tile_buffer_bytes=16777216");
    const RasterState st = raster_state_from_config(cfg);
    for (const std::string& path : shipped_scenes()) {
      const Scene scene = load_scene(path, obj_placement_from_config(cfg));
      SCOPED_TRACE(std::string(config) + " " + path);
      RenderStats imm;
      try {
        render_scene(scene, st, imm);
      } catch (const SceneError&) {
        continue;  // a scene this config does not draw (e.g. 2D with samples > 1)
      }
      if (!binned_draws(scene, st)) {
        EXPECT_THROW(render(scene, binned(st, 32, 32, BinningRule::Bbox, 1 << 24)), SceneError);
        continue;
      }
      for (int size : {8, 32, 128})
        for (BinningRule rule : {BinningRule::Bbox, BinningRule::Exact})
          // The small buffer holds one triangle listed in every bin (and a clear), no more.
          for (uint64_t pb : {uint64_t{1} << 30, 80 + 4 * bin_count(st, size)}) {
            SCOPED_TRACE("bin " + std::to_string(size) + (rule == BinningRule::Exact ? " exact" : " bbox") + " pb " +
                         std::to_string(pb));
            const RenderStats b = render(scene, binned(st, size, size, rule, pb));
            EXPECT_EQ(b.framebuffer_crc32, imm.framebuffer_crc32);
            overflows += b.bin.bin_overflows;
          }
      ++compared;
    }
  }
  EXPECT_GE(compared, 16);
  EXPECT_GT(overflows, 0u);
}

// The config keys reach RasterState, and the tile buffer must hold a bin.
TEST(Binning, ConfigKeys) {
  Config cfg;
  for (const char* s : {"pipeline.mode=binned", "bin.width=16", "bin.height=64", "bin.binning=exact",
                        "bin.load_color=true", "bin.store_depth=true", "bin.parameter_buffer_bytes=5000"})
    cfg.apply_override(s);
  const RasterState st = raster_state_from_config(cfg);
  EXPECT_EQ(st.bin.mode, PipelineMode::Binned);
  EXPECT_EQ(st.bin.width, 16);
  EXPECT_EQ(st.bin.height, 64);
  EXPECT_EQ(st.bin.rule, BinningRule::Exact);
  EXPECT_TRUE(st.bin.load_color);
  EXPECT_FALSE(st.bin.load_depth);
  EXPECT_TRUE(st.bin.store_depth);
  EXPECT_EQ(st.bin.parameter_buffer_bytes, 5000u);
  EXPECT_THROW(cfg.apply_override("bin.width=24"), ConfigError);
  EXPECT_THROW(cfg.apply_override("bin.width=256"), ConfigError);
  Config small = cfg;
  small.apply_override("bin.tile_buffer_bytes=1000");
  EXPECT_THROW(raster_state_from_config(small), ConfigError);
  Config scan = cfg;
  scan.apply_override("raster.traversal=scanline");
  EXPECT_THROW(raster_state_from_config(scan), ConfigError);
}

// Memory clients (ref/memory/bin_memory.h, docs/binning.md "Memory clients"): the
// hand-worked scene's triangles through a Binner with a BinMemory, every transfer seen.
struct Transfers {
  std::vector<MemoryTransfer> binning, tile_store;
  void attach(BinMemory& m) {
    m.on_transfer = [this](BinMemory::Client c, const MemoryTransfer& t) {
      (c == BinMemory::Client::Binning ? binning : tile_store).push_back(t);
    };
  }
};

MemoryParams linear_memory() {
  Config cfg;
  cfg.apply_override("memory.model=dram");
  cfg.apply_override("memory.fb_layout=linear");
  return memory_params_from_config(cfg);
}

// The hand scene's clear, D and A binned (32 x 32 bins, bbox) into a `pb`-byte buffer;
// nothing drawn (the addresses do not depend on it).
void bin_hand_scene(const RasterState& st, BinMemory& mem, uint64_t pb) {
  const RasterState b = binned(st, 32, 32, BinningRule::Bbox, pb);
  Framebuffer fb(64, 64, 1);
  BinStats stats;
  Binner binner(b, traversal_params(b), fb, [](const SetupTriangle&, const SetupTriangle&) {}, stats, &mem);
  binner.add_clear_color(10, 20, 30, {"hand", 2});
  for (double side : {62.0, 20.0}) {
    const ScreenTriangle v{screen_vertex(2, 2, 0.5, 1), screen_vertex(side, 2, 0.5, 1), screen_vertex(2, side, 0.5, 1)};
    SetupTriangle tri;
    ASSERT_EQ(setup_triangle(v, b, {"hand", 3}, tri), SetupOutcome::Accepted);
    binner.add_triangle(tri, {"hand", 3});
  }
  binner.finish();
}

std::vector<std::pair<uint64_t, uint64_t>> spans(const std::vector<MemoryTransfer>& ts, bool write) {
  std::vector<std::pair<uint64_t, uint64_t>> out;
  for (const MemoryTransfer& t : ts)
    if (t.write == write) out.emplace_back(t.address, t.bytes);
  return out;
}

// By hand, base B = 2^31, top T = B + 2^20: records upwards (clear 16 at B, D 64 at B + 16,
// A 64 at B + 80), entries downwards (D's bins 0..3 at T - 4 .. T - 16, A's bin 0 at T - 20).
// Reads bin by bin: the clear, then each entry and the record it names. Colour stores on
// a linear 64-px-wide surface at 0: a bin row is 32 px = 128 bytes, rows 256 bytes apart,
// so 32 transfers a bin and every byte of the 16384 written once.
TEST(Binning, MemoryClientsHandWorked) {
  const uint64_t B = uint64_t{1} << 31, T = B + (1 << 20);
  BinMemory mem(linear_memory(), 64, 64, 1, 24, B, 1 << 20);
  Transfers seen;
  seen.attach(mem);
  bin_hand_scene(hand_state(), mem, 1 << 20);
  using S = std::vector<std::pair<uint64_t, uint64_t>>;
  EXPECT_EQ(spans(seen.binning, true),
            (S{{B, 16}, {B + 16, 64}, {T - 4, 4}, {T - 8, 4}, {T - 12, 4}, {T - 16, 4}, {B + 80, 64}, {T - 20, 4}}));
  EXPECT_EQ(spans(seen.binning, false), (S{{B, 16}, {T - 4, 4}, {B + 16, 64}, {T - 20, 4}, {B + 80, 64},  // bin 0
                                           {B, 16}, {T - 8, 4}, {B + 16, 64},                             // bin 1
                                           {B, 16}, {T - 12, 4}, {B + 16, 64},                            // bin 2
                                           {B, 16}, {T - 16, 4}, {B + 16, 64}}));                         // bin 3
  EXPECT_EQ(mem.binning_stats().bytes_written, 164u);
  EXPECT_EQ(mem.binning_stats().bytes_read, 404u);
  EXPECT_EQ(seen.tile_store.size(), 128u);
  std::vector<int> written(64 * 64 * 4, 0);
  for (const MemoryTransfer& t : seen.tile_store) {
    ASSERT_TRUE(t.write);
    ASSERT_LE(t.address + t.bytes, written.size());
    for (uint64_t a = t.address; a < t.address + t.bytes; ++a) ++written[a];
  }
  EXPECT_TRUE(std::all_of(written.begin(), written.end(), [](int n) { return n == 1; }));
  EXPECT_EQ(mem.tile_store_stats().bytes_written, 16384u);
}

// A tiled colour surface (8 x 8 tiles, 4 bytes a sample, 640 px wide: 80 tiles a row,
// tile (tx, ty) at (80 ty + tx) x 256): the 32 x 32 bin at (32, 32) covers tiles 4..7 of
// rows 4..7, each row of 4 tiles one run of 1024 bytes at (80 ty + 4) x 256.
TEST(Binning, MemoryClientsTiledRuns) {
  Config cfg;
  cfg.apply_override("memory.model=dram");
  cfg.apply_override("memory.fb_layout=tiled");
  cfg.apply_override("memory.fb_tile_width=8");
  cfg.apply_override("memory.fb_tile_height=8");
  BinMemory mem(memory_params_from_config(cfg), 640, 480, 1, 24, uint64_t{1} << 31, 4096);
  Transfers seen;
  seen.attach(mem);
  mem.color({32, 32, 64, 64}, true);
  using S = std::vector<std::pair<uint64_t, uint64_t>>;
  S want;
  for (uint64_t ty = 4; ty < 8; ++ty) want.emplace_back((80 * ty + 4) * 256, 1024);
  EXPECT_EQ(spans(seen.tile_store, true), want);
}

// The 120-byte buffer: A does not fit, the overflow pass renders, and A's record and
// entry start the buffer afresh at B and T - 4 (T = B + 120). Each bin's colour and depth
// are stored (depth surface at memory.depth_base = 2^30, 4 bytes a sample), bin 0
// reloads both.
TEST(Binning, MemoryClientsOverflowAddresses) {
  const uint64_t B = uint64_t{1} << 31, T = B + 120;
  const MemoryParams p = linear_memory();
  BinMemory mem(p, 64, 64, 1, 24, B, 120);
  Transfers seen;
  seen.attach(mem);
  bin_hand_scene(hand_state(), mem, 120);
  using S = std::vector<std::pair<uint64_t, uint64_t>>;
  EXPECT_EQ(spans(seen.binning, true),
            (S{{B, 16}, {B + 16, 64}, {T - 4, 4}, {T - 8, 4}, {T - 12, 4}, {T - 16, 4}, {B, 64}, {T - 4, 4}}));
  uint64_t depth_written = 0, depth_read = 0, color_read = 0;
  for (const MemoryTransfer& t : seen.tile_store) {
    const bool depth = t.address >= p.depth_base;
    EXPECT_LE(t.address + t.bytes, (depth ? p.depth_base : p.color_base) + 64 * 64 * 4);
    if (depth) (t.write ? depth_written : depth_read) += t.bytes;
    else if (!t.write) color_read += t.bytes;
  }
  EXPECT_EQ(depth_written, 16384u);  // 4 bins at the overflow
  EXPECT_EQ(depth_read, 4096u);      // bin 0 reloads
  EXPECT_EQ(color_read, 4096u);
  EXPECT_EQ(mem.tile_store_stats().bytes_written + mem.tile_store_stats().bytes_read, 45056u);
}

// With memory.model = dram the image is the same and the clients' bytes are the binner's
// (the ROP's clients move nothing: it writes the tile buffer), 1 and 4 samples, tiled
// surfaces, overflow or not.
TEST(Binning, MemoryClientsRandomScenes) {
  std::mt19937 rng(2929);
  const Scene scene = random_scene(rng, 200, 150, 300);
  for (int samples : {1, 4}) {
    Config cfg;
    cfg.apply_override("memory.model=dram");
    cfg.apply_override("memory.fb_layout=tiled");
    cfg.apply_override("display.width=200");
    cfg.apply_override("display.height=150");
    cfg.apply_override("raster.samples=" + std::to_string(samples));
    const MemoryParams mp = memory_params_from_config(cfg);
    const RasterState st = raster_state_from_config(cfg);
    RenderStats imm;
    render_scene(scene, st, imm);
    for (int size : {8, 32, 128})
      for (uint64_t pb : {uint64_t{1} << 24, uint64_t{4096}}) {
        SCOPED_TRACE("samples " + std::to_string(samples) + " bin " + std::to_string(size) + " pb " + std::to_string(pb));
        RenderStats b;
        render_scene(scene, binned(st, size, size, BinningRule::Bbox, pb), b, {}, Framebuffer::kDefaultTileLog2, 1, mp);
        EXPECT_EQ(b.framebuffer_crc32, imm.framebuffer_crc32);
        ASSERT_TRUE(b.memory.binned);
        EXPECT_EQ(b.memory.binning.bytes_written, b.bin.geometry_bytes_written);
        EXPECT_EQ(b.memory.binning.bytes_read, b.bin.geometry_bytes_read);
        EXPECT_EQ(b.memory.tile_store.bytes_written, b.bin.framebuffer_bytes_written);
        EXPECT_EQ(b.memory.tile_store.bytes_read, b.bin.framebuffer_bytes_read);
        EXPECT_EQ(b.memory.rop_color.accesses + b.memory.rop_depth.accesses, 0u);
      }
  }
}

// memory.model = dram is taken in binned mode; a parameter buffer over a surface is not.
TEST(Binning, MemoryConfig) {
  Config cfg;
  cfg.apply_override("pipeline.mode=binned");
  cfg.apply_override("memory.model=dram");
  EXPECT_EQ(raster_state_from_config(cfg).bin.mode, PipelineMode::Binned);
  EXPECT_NO_THROW(memory_params_from_config(cfg));
  cfg.apply_override("bin.parameter_buffer_base=4096");  // inside the colour surface at 0
  EXPECT_THROW(memory_params_from_config(cfg), ConfigError);
}

}  // namespace
}  // namespace rastsim
