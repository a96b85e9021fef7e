// SPDX-License-Identifier: Apache-2.0
// The timed texture stage (model/sc/texture.h, docs/texture.md "Timed texture stage"):
// simulate draws textured scenes bit-identical to render (image, fragment stream, every
// counter, the texture stats included) for every filter, mipmaps on and off and every
// wrap, with untextured batches and state commands between textured ones (the fences);
// its busy cycles follow the stated equation on a hand-worked scene; an untextured scene
// never reaches it; memory.model = "dram" refuses a textured scene naming the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "config/obj_placement.h"
#include "estimate/estimate.h"
#include "scene/scene_io.h"
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
// fragments a cycle), a batch of n fragments costs n sample slots (nearest, bilinear) or
// 2n (trilinear), so the stage is busy 256 (or 512) + 4 x texture.miss_cycles = 100.
TEST(ScTextureTiming, BusyCyclesFollowTheEquation) {
  TexScratch s;
  const std::string tex = s.random_tga("c.tga", 8, 8, 3);
  const std::vector<std::string> cfg = {"raster.tile_size=16",        "texture.bilinear_per_cycle=1",
                                        "texture.quads_per_cycle=64", "texture.texels_per_cycle=256",
                                        "texture.combine_per_cycle=64", "texture.miss_cycles=100"};
  const std::pair<std::string, uint64_t> filters[] = {{"nearest", 1}, {"bilinear", 1}, {"trilinear", 2}};
  for (const auto& [filter, slots] : filters) {
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
    EXPECT_EQ(st["stages"]["texture"]["busy"].get<uint64_t>(), 256 * slots + 4 * 100);
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

TEST(ScTextureTiming, DramMemoryRefusesATexturedScene) {
  TexScratch s;
  const std::string tex = s.random_tga("d.tga", 4, 4, 5);
  const Scene scene = parse_trace("texture 1 " + tex + "\nbindtexture 1\ntri 0 0 9 0 0 9\n", "d.trace");
  const Config cfg = sctest::make_config({"memory.model=dram"});
  const nlohmann::json j = sctest::run_isolated([&] { return sctest::simulate_stats(scene, cfg); });
  ASSERT_TRUE(j.contains("error"));
  const std::string e = j["error"];
  EXPECT_NE(e.find("memory.model = \"dram\""), std::string::npos) << e;
  EXPECT_NE(e.find("texture.miss_cycles"), std::string::npos) << e;
  EXPECT_NE(e.find("d.tga"), std::string::npos) << e;
}

}  // namespace
}  // namespace rastsim
