// SPDX-License-Identifier: Apache-2.0
// `rastsim area --top rast_texture_lod` / `rast_texture_address` build the texture unit's
// LOD and address units with the config's TextureRtlParams (rtlsim/rtl_params.h
// root_rtl_params: interp.texcoord_format, texture.weight_bits, the largest texture and
// bias, texture.base's range); the filter and the combine take none (docs/texture.md "RTL").
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common.h"
#include "rtlsim/area.h"
#include "rtlsim/area_memory.h"
#include "rtlsim/rtl_params.h"
#include "util/process.h"

namespace rastsim {
namespace {

ArchParams texture_arch(const std::vector<std::string>& sets) {
  app::ConfigOptions c;
  c.sets = sets;
  return ArchParams::resolve(app::load_config(c));
}

// By hand: s7.20 (the default interp.texcoord_format) is 28 bits, 20 of them fraction; a
// side of up to 16384 texels needs 15 bits and its 15 levels (0..14) 4; 256 x 16 = 4096
// needs 13 bits and a sign; texture.base up to 2^40 needs 41 bits, and one more.
TEST(AreaTextureParams, FromTheConfig) {
  using P = std::vector<std::pair<std::string, int>>;
  const ArchParams d = texture_arch({});
  EXPECT_EQ(root_rtl_params("rast_texture_lod", d),
            (P{{"TexW", 28}, {"TexFrac", 20}, {"SizeW", 15}, {"LevelW", 4}, {"BiasW", 14}}));
  EXPECT_EQ(root_rtl_params("rast_texture_address", d),
            (P{{"TexW", 28}, {"TexFrac", 20}, {"WeightBits", 8}, {"SizeW", 15}, {"AddrW", 42}}));
  const ArchParams n = texture_arch({"texture.weight_bits=5", "interp.texcoord_format=s3.12"});
  EXPECT_EQ(root_rtl_params("rast_texture_address", n),
            (P{{"TexW", 16}, {"TexFrac", 12}, {"WeightBits", 5}, {"SizeW", 15}, {"AddrW", 42}}));
  EXPECT_TRUE(root_rtl_params("rast_texture_filter", d).empty());
  EXPECT_TRUE(root_rtl_params("rast_texture_combine", d).empty());
  EXPECT_EQ(root_rtl_param_names("rast_texture_lod"),
            (std::vector<std::string>{"TexW", "TexFrac", "SizeW", "LevelW", "BiasW"}));
}

// The texture cache (rtl/rast_texture_cache.sv) by hand: the default 16 KiB, 4 ways,
// 64-byte lines; Ports = ceil(16 texels / 4 bilinear lanes) = 4, ceil(3 / 4) = 1, and
// ceil(100 / 4) = 25 clamped to 4; BeatBytes min(line, 16). Its data: Ports copies of
// 16384 x 8 = 131,072 bits, each 6 x 131,072 = 786,432 cell transistors + 10 % periphery
// (78,643) = 865,075. No cache (texture.cache_bytes 0): refused, naming the key.
TEST(AreaTextureParams, Cache) {
  using P = std::vector<std::pair<std::string, int>>;
  const ArchParams d = texture_arch({});
  EXPECT_EQ(root_rtl_params("rast_texture_cache", d), (P{{"AddrW", 42}, {"CacheBytes", 16384}, {"Ways", 4},
                                                         {"LineBytes", 64}, {"Ports", 4}, {"BeatBytes", 16}}));
  const ArchParams n = texture_arch({"texture.texels_per_cycle=3", "texture.line_bytes=8", "texture.ways=2",
                                     "texture.cache_bytes=256"});
  EXPECT_EQ(root_rtl_params("rast_texture_cache", n), (P{{"AddrW", 42}, {"CacheBytes", 256}, {"Ways", 2},
                                                         {"LineBytes", 8}, {"Ports", 1}, {"BeatBytes", 8}}));
  EXPECT_EQ(root_rtl_params("rast_texture_cache", texture_arch({"texture.texels_per_cycle=100"}))[4],
            (std::pair<std::string, int>{"Ports", 4}));
  EXPECT_EQ(root_rtl_param_names("rast_texture_cache"),
            (std::vector<std::string>{"AddrW", "CacheBytes", "Ways", "LineBytes", "Ports", "BeatBytes"}));
  try {
    root_rtl_params("rast_texture_cache", texture_arch({"texture.cache_bytes=0"}));
    ADD_FAILURE() << "no cache accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("texture.cache_bytes is 0"), std::string::npos) << e.what();
  }
  const std::vector<StorageArray> data = texture_cache_data_storage(d);
  ASSERT_EQ(data.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(data[k].name, "texture_cache.copy" + std::to_string(k) + ".data");
    EXPECT_EQ(data[k].bits, 131072u);
    EXPECT_TRUE(data[k].sram);
    EXPECT_EQ(data[k].transistors, 865075u);
  }
}

// rast_top holds the texture cache (g_tex_cache) with its data copies as blackboxes: `--top
// rast_top` and the whole design count them (4 x 131,072 bits at the default, 865,075
// transistors each: 131,072 x 6 x 1.1, rounded down) after the fragment FIFO's beats
// (AreaMemory.FragmentFifoBeats), the whole design after the memory system's arrays; no
// cache, no cache rows.
TEST(AreaTextureParams, RastTopCountsTheCacheData) {
  const ArchParams d = texture_arch({"memory.model=dram"});
  const std::vector<StorageArray> top = rast_top_storage(d);
  ASSERT_EQ(top.size(), 5u);
  EXPECT_EQ(top[0].name, "fragment_fifo.beats");
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(top[k + 1].name, "texture_cache.copy" + std::to_string(k) + ".data");
    EXPECT_EQ(top[k + 1].transistors, 865075u);
  }
  const std::vector<StorageArray> mem = memory_storage(d), all = design_storage(d);
  ASSERT_FALSE(mem.empty());
  ASSERT_EQ(all.size(), mem.size() + 5);
  for (size_t k = 0; k < mem.size(); ++k) EXPECT_EQ(all[k].name, mem[k].name);
  EXPECT_EQ(all.back().name, "texture_cache.copy3.data");
  const std::vector<StorageArray> none = rast_top_storage(texture_arch({"texture.cache_bytes=0"}));
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].name, "fragment_fifo.beats");
  EXPECT_EQ(design_storage(texture_arch({"texture.cache_bytes=0", "memory.model=dram"})).size(), mem.size() + 1);
}

// The combine synthesised (a second or two: six 8 x 8 multipliers). Its flip-flops by
// hand from rtl/rast_texture_combine.sv: 2 valid bits; stage 1 the three 16-bit
// numerators (48), T's colour (24) and replace (1); stage 2 the colour (24). 99.
TEST(AreaTexture, CombineFlipFlopsByHand) {
  try {
    find_yosys();
  } catch (const std::exception&) {
    GTEST_SKIP() << "yosys not installed";
  }
  const std::filesystem::path stats =
      std::filesystem::temp_directory_path() / ("rastsim_area_texture_" + std::to_string(::getpid()) + ".json");
  ProcessOptions po;
  po.out = Sink::Capture;
  po.err = Sink::Stdout;
  const ProcessResult r = run_process(
      {RASTSIM_BINARY, "area", "--top", "rast_texture_combine", "--no-cache", "-q", "--stats", stats.string()}, po);
  ASSERT_TRUE(WIFEXITED(r.status) && WEXITSTATUS(r.status) == 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
  std::filesystem::remove(stats);
  EXPECT_EQ(j["flip_flops"], 2 + 48 + 24 + 1 + 24);
}

}  // namespace
}  // namespace rastsim
