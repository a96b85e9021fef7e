// SPDX-License-Identifier: Apache-2.0
// The timed texture stage (model/sc/texture.h, docs/texture.md "Timed texture stage"):
// simulate draws textured scenes bit-identical to render (image, fragment stream, every
// counter, the texture stats included) for every filter, mipmaps on and off and every
// wrap, with untextured batches and state commands between textured ones (the fences);
// its busy cycles follow the stated equation on a hand-worked scene; an untextured scene
// never reaches it; with memory.model = "dram" its misses are the texture client's line
// fills: render's counts, the stall rule, a bound against an infinitely fast memory, the
// fills in --mem-trace, and the crate's cycles ordered as its cache's hit rates.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <tuple>

#include <iostream>

#include "config/arch_params.h"
#include "config/obj_placement.h"
#include "estimate/estimate.h"
#include "ref/pipeline.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"
#include "util/process.h"
#include "sim_harness.h"

namespace rastsim {
namespace {

const std::string kData = std::string(RASTSIM_SOURCE_DIR) + "/tb/data";

// A scratch directory for a test's texture and trace files, removed at the end.
struct TexScratch {
  std::filesystem::path dir;
  TexScratch() {
    dir = std::filesystem::temp_directory_path() / ("rastsim_sc_texture_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~TexScratch() { std::filesystem::remove_all(dir); }
  // An uncompressed 32-bit TGA, top-left origin (descriptor 0x28), of seeded random texels.
  std::string random_tga(const std::string& name, int w, int h, uint64_t seed) const {
    std::string bytes = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, char(w & 255), char(w >> 8), char(h & 255),
                         char(h >> 8), 32, 0x28};
    std::mt19937_64 rng(seed);
    for (int k = 0; k < w * h * 4; ++k) bytes.push_back(char(rng() & 255));
    return put(name, bytes);
  }
  std::string put(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
};

// Random textured triangles over a 96 x 96 viewport with texture coordinates in three
// repeats either side (minified and magnified), one in five untextured, clears and colour
// changes between them: every transaction kind behind textured batches.
std::string random_textured_trace(const std::string& tex, const std::string& state, uint64_t seed, int triangles) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-10, 106), coord(-3, 3);
  std::uniform_int_distribution<int> pick(0, 99), colour(0, 255);
  std::ostringstream t;
  t << "viewport 96 96\nclear 10 20 30\ntexture 1 " << tex << "\n" << state << "bindtexture 1\n";
  for (int k = 0; k < triangles; ++k) {
    const int r = pick(rng);
    if (r < 5) t << "clear " << colour(rng) << " 40 50\n";
    if (r >= 5 && r < 10) t << "color " << colour(rng) << " " << colour(rng) << " 200\n";
    const bool untextured = r >= 80;
    if (untextured) t << "bindtexture none\n";
    t << "strip\n";
    for (int v = 0; v < 3; ++v) {
      t << "texcoord " << coord(rng) << " " << coord(rng) << "\n";
      t << "v " << pos(rng) << " " << pos(rng) << "\n";
    }
    t << "end\n";
    if (untextured) t << "bindtexture 1\n";
  }
  return t.str();
}

struct StateCase {
  const char* name;
  const char* state;  // trace lines before the draws
};

class ScTexture : public ::testing::TestWithParam<StateCase> {};

TEST_P(ScTexture, RandomTrianglesMatchRender) {
  TexScratch s;
  const std::string tex = s.random_tga("r.tga", 32, 16, 7);  // a non-square chain: 6 levels
  const Scene scene = parse_trace(random_textured_trace(tex, GetParam().state, 0x7e5c0001, 60), "random.trace");
  const Config cfg = sctest::make_config({"texture.cache_bytes=1024"});
  const nlohmann::json r = sctest::run_isolated([&] { return sctest::compare_with_reference(scene, cfg); });
  sctest::expect_matches_reference(r);
  ASSERT_FALSE(r.contains("error"));
  const auto& st = r["stats"];
  EXPECT_GT(st["texel_fetches"].get<uint64_t>(), 0u);
  EXPECT_GT(st["texture_cache_misses"].get<uint64_t>(), 0u);
  EXPECT_GT(st["helper_pixels"].get<uint64_t>(), 0u);
  EXPECT_GT(st["stages"]["texture"]["busy"].get<uint64_t>(), 0u);
  EXPECT_GT(st["fifos"]["texture_done"]["transactions"].get<uint64_t>(), 0u);  // fences were passed
  // estimate's texture bound stays below the simulation: the stage's busy and the cycles.
  const EstimateResult e = estimate_scene(scene, ArchParams::resolve(cfg));
  EXPECT_GT(e.stages[stage_index(StageId::Texture)].busy, 0u);
  EXPECT_LE(e.stages[stage_index(StageId::Texture)].busy, st["stages"]["texture"]["busy"].get<uint64_t>());
  EXPECT_LE(e.cycles_lower_bound, st["cycles"].get<uint64_t>());
}

INSTANTIATE_TEST_SUITE_P(
    FiltersMipmapsWraps, ScTexture,
    ::testing::Values(StateCase{"NearestRepeat", "texfilter nearest\n"},
                      StateCase{"BilinearClampMirror", "texfilter bilinear\ntexwrap clamp mirror\ntexenv decal\n"},
                      StateCase{"TrilinearNoMipmap", "texfilter trilinear\ntexwrap mirror\n"},
                      StateCase{"NearestMipmap", "texfilter nearest\nmipmap on\ntexenv replace\n"},
                      StateCase{"BilinearMipmapBias", "mipmap on\ntexlod_bias -0.5\ntexwrap repeat clamp\n"},
                      StateCase{"TrilinearMipmap", "texfilter trilinear\nmipmap on\n"}),
    [](const ::testing::TestParamInfo<StateCase>& i) { return std::string(i.param.name); });

// One-entry FIFOs, no latency slots and random stalls: the fences and the merge into the
// fragment FIFO neither lose, reorder nor deadlock (Link checks the order, the run that
// every FIFO drained).
TEST(ScTextureFifo, DepthOneWithStallsMatchesRender) {
  TexScratch s;
  const std::string tex = s.random_tga("r.tga", 16, 16, 9);
  const Scene scene = parse_trace(random_textured_trace(tex, "mipmap on\n", 0x7e5c0002, 40), "random.trace");
  const Config cfg = sctest::make_config({"fifo.pixel_depth=1", "fifo.fragment_depth=1", "fifo.texture_depth=1",
                                          "interp.latency_cycles=0", "interp.perspective=false"});
  sc::SimOptions stalls;
  stalls.stall_seed = 0x5eed;
  stalls.stall_probability = 0.3;
  const nlohmann::json r = sctest::run_isolated([&] { return sctest::compare_with_reference(scene, cfg, stalls); });
  sctest::expect_matches_reference(r);
  ASSERT_FALSE(r.contains("error"));
  EXPECT_EQ(r["stats"]["fifos"]["texture_fifo"]["depth"], 1);
  EXPECT_GT(r["stats"]["fifos"]["texture_done"]["transactions"].get<uint64_t>(), 0u);
}

// The notes-style textured box (render's figures: docs/texture.md), with 2 samples (msaa)
// and with scanline traversal too, whose quads span two batches.
TEST(ScTextureBox, BoxTMatchesRender) {
  const Scene scene = load_obj(kData + "/boxT.obj", obj_placement_from_config(Config{}));
  for (const std::vector<std::string>& set : {std::vector<std::string>{}, {"raster.samples=2"},
                                             {"raster.traversal=scanline"}, {"texture.layout=morton"}}) {
    SCOPED_TRACE(set.empty() ? "defaults" : set[0]);
    const Config cfg = sctest::make_config(set);
    const nlohmann::json r = sctest::run_isolated([&] { return sctest::compare_with_reference(scene, cfg); });
    sctest::expect_matches_reference(r);
    ASSERT_FALSE(r.contains("error"));
    EXPECT_GT(r["stats"]["helper_pixels"].get<uint64_t>(), 0u);
    const EstimateResult e = estimate_scene(scene, ArchParams::resolve(cfg));
    EXPECT_LE(e.stages[stage_index(StageId::Texture)].busy, r["stats"]["stages"]["texture"]["busy"].get<uint64_t>());
    EXPECT_LE(e.cycles_lower_bound, r["stats"]["cycles"].get<uint64_t>());
  }
}

// A 16 x 16-pixel square (two triangles, one 16-pixel tile) textured with an 8 x 8 RGBA8
// texture, s and t 0 to 1 across it. Worked by hand: 256 fragments; every texel of level
// 0 read, 8 x 8 x 4 = 256 bytes from a 4096-byte aligned base, 4 lines of 64 bytes, each
// missed once (the 16 KiB cache holds them all); the diagonal x + y = 15.5 crosses the 8
// quads whose top-left pixel has x + y = 14, each shaded by both triangles (the others
// lie in one), 2 x 8 x 4 quad pixels less the 64 covered ones: 32 helper pixels. With
// texture.bilinear_per_cycle = 1 and the other units wide (64 quads, 256 texels, 64
// fragments a cycle), a batch of n fragments costs n level samples: one a fragment, also
// trilinear's, whose second level has weight 0 without mipmaps (one level read; it
// blends two, 2n, where mipmapped minification reads two), so the stage is busy 256 + S +
// 4 x texture.miss_cycles = 100, S the misses that split a lookup group
// (TimingParams::TextureWork::miss_splits: the texture cache's 4 ports look a missing
// texel up as the first of a cycle). Nearest reads a texel a request: none. Bilinear (and
// trilinear, level 0 alone without mipmaps) fetches (i0, j0), (i1, j0), (i0, j1), (i1, j1),
// u = 8 s - 1/2: the first fragment (0, 0) reads texels (7, 7) (line 3, the first texel:
// no split), (0, 7), then (7, 0) (line 0, third: a split), (0, 0); rows 2-3 of the texture
// (line 1) are first read at pixel (0, 3), texel (7, 2), third; rows 4-5 (line 2) at
// (0, 7), texel (7, 4), third: S = 3. The stage starts on the first triangle's first beat
// (docs/texture.md "Timed texture stage") and its first fragment (0, 0) waits W = 13
// cycles for its first slot: its quad's bottom-left pixel (0, 1) is pixel 2 q = 16 of row
// pair 0 (q = 8 quads, its top row's 16 pixels first), beat 4 at 4 lanes, as is the next
// fragment's (1, 0); max(4 + 1, 4) + 8 (kBeatToRequest) = 13. Nothing waits after it: the
// first fragment's misses (one nearest, two bilinear) stall 100 cycles each, far past every later beat, no beat of
// either triangle holds helper pixels only (the diagonal quads' helpers are at most two a
// row, at a row's start or end, and a row pair's 4 q pixels fill whole beats), the second
// triangle's beats came while the first was sampled, and no mipmap means no level table.
TEST(ScTextureTiming, BusyCyclesFollowTheEquation) {
  TexScratch s;
  const std::string tex = s.random_tga("c.tga", 8, 8, 3);
  const std::vector<std::string> cfg = {"raster.tile_size=16",        "texture.bilinear_per_cycle=1",
                                        "texture.quads_per_cycle=64", "texture.texels_per_cycle=256",
                                        "texture.combine_per_cycle=64", "texture.miss_cycles=100"};
  const std::tuple<std::string, uint64_t, uint64_t> filters[] = {
      {"nearest", 1, 0}, {"bilinear", 1, 3}, {"trilinear", 1, 3}};
  for (const auto& [filter, slots, splits] : filters) {
    SCOPED_TRACE(filter);
    // s, t from 0 to 1 over the square: every texel of level 0 read (one repeat).
    const Scene scene = parse_trace("viewport 32 32\ntexture 1 " + tex + "\ntexfilter " + filter +
                                        "\nbindtexture 1\nstrip\ntexcoord 0 0\nv 0 0\ntexcoord 1 0\nv 16 0\n"
                                        "texcoord 0 1\nv 0 16\ntexcoord 1 1\nv 16 16\nend\n",
                                    "square.trace");
    const Config config = sctest::make_config(cfg);
    const nlohmann::json r = sctest::run_isolated([&] { return sctest::compare_with_reference(scene, config); });
    sctest::expect_matches_reference(r);
    ASSERT_FALSE(r.contains("error"));
    const auto& st = r["stats"];
    EXPECT_EQ(st["fragments_shaded"].get<uint64_t>(), 256u);
    EXPECT_EQ(st["texture_cache_misses"].get<uint64_t>(), 4u);
    EXPECT_EQ(st["helper_pixels"].get<uint64_t>(), 32u);
    EXPECT_EQ(st["stages"]["texture"]["busy"].get<uint64_t>(), 256 * slots + splits + 4 * 100 + 13);
    // estimate: the sample-rate term alone (no misses, no quads), and no upper bound.
    const EstimateResult e = estimate_scene(scene, ArchParams::resolve(config));
    EXPECT_EQ(e.stages[stage_index(StageId::Texture)].busy, 256 * slots);
    EXPECT_FALSE(e.has_upper_bound());
    EXPECT_LE(e.cycles_lower_bound, st["cycles"].get<uint64_t>());
  }
}

// An untextured scene never reaches the texture stage: no busy cycle, no transaction.
TEST(ScTextureTiming, UntexturedSceneBypassesTheStage) {
  const Scene scene = sctest::random_scene(11, 64, 64, 40);
  const nlohmann::json j = sctest::run_isolated([&] { return sctest::simulate_stats(scene, sctest::make_config({})); });
  ASSERT_FALSE(j.contains("error")) << j["error"];
  EXPECT_EQ(j["stages"]["texture"]["busy"], 0);
  EXPECT_EQ(j["stages"]["texture"]["transactions_in"], 0);
  EXPECT_EQ(j["fifos"]["texture_fifo"]["transactions"], 0);
  EXPECT_FALSE(j.contains("texel_fetches"));
}

// memory.model = "dram" (timing/texture_memory_port.h): render's counts with the config's
// memory settings (the ROP's and the texture unit's functional caches) against
// simulate's, the images' CRCs, and simulate's stats.
nlohmann::json dram_compare(const Scene& scene, const Config& cfg, const sc::SimOptions& opts = {}) {
  const ArchParams a = ArchParams::resolve(cfg);
  RenderStats ref;
  const Framebuffer fb = render_scene(scene, a.raster, ref, {}, Framebuffer::kDefaultTileLog2, 1, a.memory);
  const sc::SimResult r = sc::simulate_scene(scene, a, opts);
  nlohmann::json rj = rastsim::to_json(ref), sj = rastsim::to_json(r.render);
  rj.erase("wall_seconds");
  sj.erase("wall_seconds");
  return {{"ref", rj}, {"sim", sj}, {"crc_ref", fb.color_crc32()}, {"crc_sim", r.fb.color_crc32()},
          {"stats", r.to_json()}};
}

// The texture client's figures against render's counts (bytes, reads) and the timing
// rule: each fill stalls from its issue to its arrival, at least the DRAM's read latency
// from its arrival (mean_read_latency_cycles), so at least a cycle.
void expect_texture_client(const nlohmann::json& r, uint64_t burst_bytes) {
  ASSERT_FALSE(r.contains("error")) << r["error"];
  EXPECT_EQ(r["sim"], r["ref"]);
  EXPECT_EQ(r["crc_sim"], r["crc_ref"]);
  const auto& st = r["stats"];
  ASSERT_TRUE(st["memory"]["clients"].contains("texture")) << st["memory"].dump();
  const auto& t = st["memory"]["clients"]["texture"];
  const uint64_t reads = t["reads"], bytes = t["bytes_read"], stall = t["stall_cycles"];
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(bytes, st["texture_dram_bytes"].get<uint64_t>());
  EXPECT_EQ(reads, st["texture_cache_misses"].get<uint64_t>());
  EXPECT_GE(t["bursts_read"].get<uint64_t>() * burst_bytes, bytes);
  EXPECT_EQ(t["bursts_written"], 0);
  EXPECT_GE(stall, reads);
  EXPECT_GE(double(stall) + 1e-6 * double(reads), t["mean_read_latency_cycles"].get<double>() * double(reads));
}

struct DramCase {
  const char* name;
  const char* state;               // trace lines before the draws
  std::vector<std::string> config;  // beyond memory.model
};

class ScTextureDram : public ::testing::TestWithParam<DramCase> {};

// Random textured triangles with the DRAM: counts equal render's; against the same scene
// with an infinitely fast texture memory (memory.model = "fixed", texture.miss_cycles =
// 0, the ROP at its fixed cost, which no DRAM fill undercuts), the texture stage is busy
// at most the fills' stall more (the fills' stall hides some of the slots' waits for
// their beats, docs/texture.md "Timed texture stage") and at least the stall more than
// estimate's rate, and the frame takes at least as long; estimate's lower bound stays
// below the DRAM run.
TEST_P(ScTextureDram, RandomTrianglesCountsAndBound) {
  TexScratch s;
  const std::string tex = s.random_tga("r.tga", 32, 16, 7);
  const Scene scene = parse_trace(random_textured_trace(tex, GetParam().state, 0x7e5c0003, 60), "random.trace");
  std::vector<std::string> kv = GetParam().config;
  kv.push_back("memory.model=dram");
  const Config dram = sctest::make_config(kv);
  kv.back() = "memory.model=fixed";
  kv.push_back("texture.miss_cycles=0");
  const Config fast = sctest::make_config(kv);
  const nlohmann::json r = sctest::run_isolated([&] { return dram_compare(scene, dram); });
  expect_texture_client(r, ArchParams::resolve(dram).dram.burst_bytes());
  const nlohmann::json f = sctest::run_isolated([&] { return sctest::simulate_stats(scene, fast); });
  ASSERT_FALSE(f.contains("error")) << f["error"];
  const auto& st = r["stats"];
  const uint64_t busy = st["stages"]["texture"]["busy"].get<uint64_t>();
  const uint64_t stall = st["memory"]["clients"]["texture"]["stall_cycles"].get<uint64_t>();
  EXPECT_LE(busy, f["stages"]["texture"]["busy"].get<uint64_t>() + stall);
  EXPECT_GE(st["cycles"].get<uint64_t>(), f["cycles"].get<uint64_t>());
  const EstimateResult e = estimate_scene(scene, ArchParams::resolve(dram));
  EXPECT_GE(busy, e.stages[stage_index(StageId::Texture)].busy + stall);
  EXPECT_LE(e.cycles_lower_bound, st["cycles"].get<uint64_t>());
  EXPECT_LE(e.stages[stage_index(StageId::Texture)].busy, st["stages"]["texture"]["busy"].get<uint64_t>());
}

INSTANTIATE_TEST_SUITE_P(
    Filters, ScTextureDram,
    ::testing::Values(DramCase{"Bilinear1KiB", "texwrap clamp mirror\n", {"texture.cache_bytes=1024"}},
                      DramCase{"TrilinearMipmapTiled", "texfilter trilinear\nmipmap on\n",
                               {"texture.cache_bytes=2048", "texture.layout=tiled"}},
                      DramCase{"NearestNoCache", "texfilter nearest\n", {"texture.cache_bytes=0"}},
                      DramCase{"Bilinear128ByteLines", "mipmap on\n", {"texture.line_bytes=128", "raster.samples=2"}}),
    [](const ::testing::TestParamInfo<DramCase>& i) { return std::string(i.param.name); });

// The notes-style box with the DRAM: render's counts (4 misses, 256 bytes: docs/texture.md);
// --mem-trace lists the texture's bursts: its READ lines at or above texture.base (the
// framebuffer lies below it) are memory.clients.texture.bursts_read.
TEST(ScTextureDram, BoxCountsAndMemTrace) {
  const Scene scene = load_obj(kData + "/boxT.obj", obj_placement_from_config(Config{}));
  const Config cfg = sctest::make_config({"memory.model=dram"});
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("sc_texture_mem_" + std::to_string(::getpid()) + ".trace")).string();
  sc::SimOptions o;
  o.mem_trace_path = path;
  const nlohmann::json r = sctest::run_isolated([&] { return dram_compare(scene, cfg, o); });
  expect_texture_client(r, ArchParams::resolve(cfg).dram.burst_bytes());
  EXPECT_EQ(r["stats"]["texture_dram_bytes"], 256);
  const uint64_t base = ArchParams::resolve(cfg).raster.texture.base;
  std::ifstream in(path);
  uint64_t texture_reads = 0, lines = 0;
  for (std::string line; std::getline(in, line); ++lines) {
    std::istringstream f(line);
    std::string addr, kind;
    f >> addr >> kind;
    texture_reads += kind == "READ" && std::stoull(addr, nullptr, 16) >= base;
  }
  std::filesystem::remove(path);
  EXPECT_GT(lines, texture_reads);  // the ROP's and the scan-out's requests too
  EXPECT_EQ(texture_reads, r["stats"]["memory"]["clients"]["texture"]["bursts_read"].get<uint64_t>());
}

// glmark2's textured crate (scripts/workloads: cube.3ds and crate-base.png, 640 x 480,
// configs/d3d11.toml; skipped without glmark2-data and assimp): render's counts with the
// DRAM at a 1 KiB and the default 16 KiB cache, and the cycles ordered as the hit rates.
TEST(ScTextureDram, CrateCyclesFollowTheHitRate) {
  TexScratch s;
  const ProcessResult w = run_process({std::string(RASTSIM_SOURCE_DIR) + "/scripts/workloads", "--no-render",
                                       "--out", s.dir.string()},
                                      {.out = Sink::Null, .err = Sink::Null});
  if (!w.ok()) GTEST_SKIP() << "scripts/workloads failed (glmark2-data, assimp-utils?)";
  std::vector<std::string> kv;
  std::ifstream sets(s.dir / "crate.set");
  for (std::string t; sets >> t;) kv.push_back(t);
  kv.insert(kv.end(), {"raster.depth_func=less", "memory.model=dram"});
  Config base;
  base.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  for (const std::string& o : kv) base.apply_override(o);
  const Scene scene = load_obj((s.dir / "crate.obj").string(), obj_placement_from_config(base));
  nlohmann::json runs[2];
  const int kib[2] = {1, 16};
  for (int k = 0; k < 2; ++k) {
    Config cfg = base;
    cfg.apply_override("texture.cache_bytes=" + std::to_string(kib[k] * 1024));
    cfg.validate();
    runs[k] = sctest::run_isolated([&] { return dram_compare(scene, cfg); });
    SCOPED_TRACE(kib[k]);
    expect_texture_client(runs[k], ArchParams::resolve(cfg).dram.burst_bytes());
  }
  const auto& small = runs[0]["stats"];
  const auto& large = runs[1]["stats"];
  std::cout << "crate, DRAM: 1 KiB " << small["texture_cache_misses"] << " misses, " << small["cycles"]
            << " cycles; 16 KiB " << large["texture_cache_misses"] << " misses, " << large["cycles"] << " cycles\n";
  EXPECT_GT(small["texture_cache_misses"].get<uint64_t>(), large["texture_cache_misses"].get<uint64_t>());
  EXPECT_GT(small["cycles"].get<uint64_t>(), large["cycles"].get<uint64_t>());
  EXPECT_GT(small["stages"]["texture"]["busy"].get<uint64_t>(), large["stages"]["texture"]["busy"].get<uint64_t>());
}

}  // namespace
}  // namespace rastsim
