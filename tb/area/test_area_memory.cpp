// SPDX-License-Identifier: Apache-2.0
// The memory system's storage in `rastsim area` (model/rtlsim/area_memory.h): every array's
// bits and transistors for two configs, worked by hand below from docs/memory.md's cache
// geometry and docs/area.md's counting rule (no Yosys: milliseconds).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "common.h"
#include "rtlsim/area.h"
#include "rtlsim/area_memory.h"
#include "rtlsim/rtl_params.h"

namespace rastsim {
namespace {

std::map<std::string, StorageArray> storage_of(const std::vector<std::string>& sets) {
  app::ConfigOptions c;
  c.sets = sets;
  std::map<std::string, StorageArray> by_name;
  for (const StorageArray& a : memory_storage(app::resolve_arch(c))) by_name[a.name] = a;
  return by_name;
}

void expect_array(const std::map<std::string, StorageArray>& s, const std::string& name, uint64_t bits, bool sram,
                  uint64_t transistors) {
  SCOPED_TRACE(name);
  ASSERT_TRUE(s.count(name));
  EXPECT_EQ(s.at(name).bits, bits);
  EXPECT_EQ(s.at(name).sram, sram);
  EXPECT_EQ(s.at(name).transistors, transistors);
}

// 640 x 480 (s15.8 coordinates, as d3d11.toml), one sample, 24-bit depth (4 bytes a sample), linear, the default caches (16
// KiB, 4 ways, 64-byte lines), fast clear on 8 x 8 blocks.
// - Each surface: 640 x 480 x 4 = 1,228,800 bytes; the last offset 1,228,799 needs 21 bits
//   (2^20 <= it < 2^21). A cache: 16384 / 64 = 256 lines, 256 / 4 = 64 sets; tag = 21 - 6
//   (line) - 6 (set) = 9 bits.
// - data 16384 x 8 = 131,072 bits, SRAM: 6 x 131,072 = 786,432 + 10 % (78,643) = 865,075.
// - tags 256 x 9 = 2,304 bits, flip-flops: x 40 = 92,160.
// - state 256 x (valid 1 + dirty 1 + LRU rank 2) = 1,024 bits: x 40 = 40,960.
// - fast-clear flags 80 x 60 = 4,800 blocks a surface, SRAM: 28,800 + 2,880 = 31,680.
TEST(AreaMemory, HandWorkedDefaultCachesWithFastClear) {
  const auto s = storage_of({"display.width=640", "display.height=480", "raster.coord_format=s15.8", "raster.samples=1",
                             "raster.depth_bits=24", "memory.model=dram", "rop.fast_clear=true"});
  EXPECT_EQ(s.size(), 8u);
  for (const std::string cache : {"rop_color_cache", "rop_depth_cache"}) {
    expect_array(s, cache + ".data", 131072, true, 865075);
    expect_array(s, cache + ".tags", 2304, false, 92160);
    expect_array(s, cache + ".state", 1024, false, 40960);
  }
  expect_array(s, "rop_color.fast_clear_flags", 4800, true, 31680);
  expect_array(s, "rop_depth.fast_clear_flags", 4800, true, 31680);
}

// 100 x 50, 4 samples, 16-bit depth (2 bytes), plane compression on 8 x 8 blocks, no fast
// clear; a 1 KiB 2-way colour cache of 32-byte lines, a 32 KiB 4-way depth cache.
// - Colour, linear: 100 x 50 x 4 x 4 = 80,000 bytes, last offset 79,999: 17 bits. 1024 / 32
//   = 32 lines, 16 sets: tag 17 - 5 - 4 = 8. data 8,192 bits, SRAM: 49,152 + 4,915 = 54,067;
//   tags 32 x 8 = 256 bits: 10,240; state 32 x (2 + 1) = 96 bits: 3,840.
// - Depth, tiled by the 8 x 8 block (compression): 13 x 7 tiles (edges padded) x 64 px x 4
//   x 2 = 46,592 bytes, last offset 46,591: 16 bits. A line is one block, 8 x 8 x 4 x 2 =
//   512 bytes: 32768 / 512 = 64 lines, 16 sets: tag 16 - 9 - 4 = 3. data 262,144 bits:
//   1,572,864 + 157,286 = 1,730,150; tags 64 x 3 = 192 bits: 7,680; state 64 x 4 = 256
//   bits: 10,240.
// - Compression flags: 13 x 7 = 91 blocks: 3,640.
TEST(AreaMemory, HandWorkedPlaneCompressionPaddedSurface) {
  const auto s = storage_of({"display.width=100", "display.height=50", "raster.samples=4", "raster.depth_bits=16",
                             "memory.model=dram", "rop.depth_compression=plane", "rop.color_cache_bytes=1024",
                             "rop.color_cache_ways=2", "rop.color_cache_line_bytes=32", "rop.depth_cache_bytes=32768"});
  EXPECT_EQ(s.size(), 7u);
  expect_array(s, "rop_color_cache.data", 8192, true, 54067);
  expect_array(s, "rop_color_cache.tags", 256, false, 10240);
  expect_array(s, "rop_color_cache.state", 96, false, 3840);
  expect_array(s, "rop_depth_cache.data", 262144, true, 1730150);
  expect_array(s, "rop_depth_cache.tags", 192, false, 7680);
  expect_array(s, "rop_depth_cache.state", 256, false, 10240);
  expect_array(s, "rop_depth.compression_flags", 91, false, 3640);
}

// memory.model = fixed models no memory: nothing to count. A cache of 0 bytes has no arrays.
TEST(AreaMemory, NothingWithoutTheMemorySystemOrACache) {
  EXPECT_TRUE(storage_of({"memory.model=fixed", "rop.fast_clear=true"}).empty());
  const auto s = storage_of({"memory.model=dram", "rop.color_cache_bytes=0"});
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(s.count("rop_color_cache.data"), 0u);
  EXPECT_EQ(s.count("rop_depth_cache.data"), 1u);
}

// The tile buffer's arrays (binned mode, rtl/rast_tile_buffer_data.sv, a blackbox to Yosys),
// by hand: a sample is a 32-bit colour word and a depth word, each with a valid bit.
// - The default 256 KiB at 24-bit depth (4 + 4 bytes a sample): 262,144 / 8 = 32,768
//   samples. Colour 32,768 x 33 = 1,081,344 bits, SRAM: 6,488,064 + 10 % (648,806) =
//   7,136,870; depth 32,768 x 25 = 819,200 bits: 4,915,200 + 491,520 = 5,406,720.
// - 512 bytes at 16-bit depth (4 + 2 bytes): 85 samples (510 bytes). Colour 85 x 33 =
//   2,805 bits, depth 85 x 17 = 1,445, both under 4,096: flip-flops, x 40 = 112,200 and
//   57,800.
// - Immediate mode: no tile buffer, no rows; rast_top's rows are the texture cache's
//   copies, then the tile buffer's.
TEST(AreaMemory, TileBufferArrays) {
  const auto rows = [](const std::vector<std::string>& sets) {
    app::ConfigOptions c;
    c.sets = sets;
    std::map<std::string, StorageArray> by_name;
    for (const StorageArray& a : tile_buffer_storage(app::resolve_arch(c))) by_name[a.name] = a;
    return by_name;
  };
  const auto d = rows({"pipeline.mode=binned"});
  EXPECT_EQ(d.size(), 2u);
  expect_array(d, "tile_buffer.color", 1081344, true, 7136870);
  expect_array(d, "tile_buffer.depth", 819200, true, 5406720);
  const auto s = rows({"pipeline.mode=binned", "bin.width=8", "bin.height=8", "bin.tile_buffer_bytes=512",
                       "raster.depth_bits=16"});
  EXPECT_EQ(s.size(), 2u);
  expect_array(s, "tile_buffer.color", 2805, false, 112200);
  expect_array(s, "tile_buffer.depth", 1445, false, 57800);
  EXPECT_TRUE(rows({}).empty());
  app::ConfigOptions c;
  c.sets = {"pipeline.mode=binned"};
  const std::vector<StorageArray> top = rast_top_storage(app::resolve_arch(c));
  ASSERT_EQ(top.size(), 7u);  // the fragment FIFO, the default texture cache's 4 copies, the tile buffer
  EXPECT_EQ(top[0].name, "fragment_fifo.beats");
  EXPECT_EQ(top[4].name, "texture_cache.copy3.data");
  EXPECT_EQ(top[5].name, "tile_buffer.color");
  EXPECT_EQ(top[6].name, "tile_buffer.depth");
}

// The fragment FIFO's ring of beats (rtl/rast_fragment_fifo_data.sv in rast_top, a blackbox
// to Yosys): FragBeats x BeatW bits, by hand from rast_top.sv's localparams. PixelW is 14
// in every config (the schema's largest display side, 16,384 - 1).
// - The default: Lanes = interp.fragments_per_cycle = 4, perspective built with 4 recip
//   lanes: TileBeats = 16 x 16 / 4 = 64; FragmentFifoEntries = fifo.fragment_depth 4 +
//   interp.latency_cycles 6 + the reciprocal's 2 + 2 x 2 = 16, FragBeats = (16 + 3) x 64 =
//   1,216. A beat: marker and last (2) + 4 lanes x (lane bit 1 + x, y 28 + depth 24 +
//   colour 24 + MaxSamples 16 = 93) = 374 bits. 1,216 x 374 = 454,784 bits, SRAM: 6 x
//   454,784 = 2,728,704 + 10 % (272,870) = 3,001,574.
// - Affine, 2 lanes, 8 x 8 tiles, fragment_depth 2, latency 3, 16-bit depth, 4 samples:
//   TileBeats 64 / 2 = 32; entries 2 + 3 = 5, FragBeats 8 x 32 = 256; a beat 2 + 2 x (1 +
//   28 + 16 + 24 + 4 = 73) = 148 bits; 37,888 bits: 227,328 + 22,732 = 250,060.
// - The default with recip.lanes = 2: a perspective beat holds 2 fragments, TileBeats 256 /
//   2 = 128, FragBeats 19 x 128 = 2,432; 2,432 x 374 = 909,568 bits: 5,457,408 + 545,740
//   = 6,003,148.
// It is rast_top's first row, before the texture cache's copies.
TEST(AreaMemory, FragmentFifoBeats) {
  const auto row = [](const std::vector<std::string>& sets) {
    app::ConfigOptions c;
    c.config_path = std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml";
    c.sets = sets;
    const StorageArray a = fragment_fifo_storage(rtl_params(app::resolve_arch(c)));
    return std::map<std::string, StorageArray>{{a.name, a}};
  };
  expect_array(row({}), "fragment_fifo.beats", 454784, true, 3001574);
  expect_array(row({"interp.perspective=false", "interp.fragments_per_cycle=2", "raster.tile_size=8",
                    "fifo.fragment_depth=2", "interp.latency_cycles=3", "raster.depth_bits=16",
                    "raster.max_samples=4", "raster.samples=4"}),
               "fragment_fifo.beats", 37888, true, 250060);
  expect_array(row({"recip.lanes=2"}), "fragment_fifo.beats", 909568, true, 6003148);
  app::ConfigOptions c;
  c.config_path = std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml";
  const std::vector<StorageArray> top = rast_top_storage(app::resolve_arch(c));
  ASSERT_FALSE(top.empty());
  EXPECT_EQ(top[0].name, "fragment_fifo.beats");
  EXPECT_EQ(top[0].bits, 454784u);
}

// The rows reach the report's total and its JSON, in order, and come back from it.
TEST(AreaMemory, RowsInTotalAndJson) {
  AreaReport r;
  r.total.transistors = 1000;
  add_storage(r, {{"a.data", 8192, true, 54067}, {"a.tags", 8, false, 320}});
  EXPECT_EQ(r.total.transistors, 1000u + 54067u + 320u);
  const nlohmann::json j = area_to_json(r);
  ASSERT_EQ(j.at("storage").size(), 2u);
  EXPECT_EQ(j["storage"][0]["name"], "a.data");
  EXPECT_EQ(j["storage"][0]["kind"], "sram");
  EXPECT_EQ(j["storage"][1]["kind"], "flip_flops");
  EXPECT_EQ(j["transistors"], 55387);
  const AreaReport back = area_from_json(j);
  ASSERT_EQ(back.storage.size(), 2u);
  EXPECT_EQ(back.storage[1].name, "a.tags");
  EXPECT_EQ(back.storage[1].bits, 8u);
  EXPECT_FALSE(back.storage[1].sram);
  EXPECT_EQ(back.storage[1].transistors, 320u);
}

}  // namespace
}  // namespace rastsim
