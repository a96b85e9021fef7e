// SPDX-License-Identifier: Apache-2.0
// `rastsim area --top rast_rop_cache` builds the ROP's cache (rtl/rast_rop_cache.sv) with
// the colour cache's parameters (rtlsim/rtl_params.h rop_cache_rtl_params) and counts its
// data array, a blackbox to Yosys, as a storage row (rtlsim/area_memory.h).
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
#include "rtlsim/rtl_params.h"
#include "util/process.h"

namespace rastsim {
namespace {

ArchParams rop_cache_arch(const std::vector<std::string>& sets) {
  app::ConfigOptions c;
  c.sets = sets;
  return ArchParams::resolve(app::load_config(c));
}

// AddrW by hand: the colour surface's last byte offset. 128 x 128 x 4 bytes = 65,536: 16
// bits; 200 x 150 x 4 = 120,000: 17 bits (2^16 < 119,999 < 2^17); four samples of
// 128 x 128: 262,144 bytes, 18 bits.
TEST(AreaRopCacheParams, TheColourCacheOverItsSurface) {
  using P = std::vector<std::pair<std::string, int>>;
  EXPECT_EQ(root_rtl_params("rast_rop_cache", rop_cache_arch({})),  // the default config: 128 x 128, 16 KiB 4-way 64 B
            (P{{"AddrW", 16}, {"CacheBytes", 16384}, {"Ways", 4}, {"LineBytes", 64}, {"WordBytes", 4}}));
  const ArchParams small = rop_cache_arch({"display.width=200", "display.height=150", "rop.color_cache_bytes=4096",
                                         "rop.color_cache_ways=2", "rop.color_cache_line_bytes=32"});
  EXPECT_EQ(root_rtl_params("rast_rop_cache", small),
            (P{{"AddrW", 17}, {"CacheBytes", 4096}, {"Ways", 2}, {"LineBytes", 32}, {"WordBytes", 4}}));
  EXPECT_EQ(rop_cache_rtl_params(rop_cache_arch({"raster.max_samples=4", "raster.samples=4"})).addr_w, 18);
  EXPECT_EQ(root_rtl_param_names("rast_rop_cache"),
            (std::vector<std::string>{"AddrW", "CacheBytes", "Ways", "LineBytes", "WordBytes"}));
  try {
    root_rtl_params("rast_rop_cache", rop_cache_arch({"rop.color_cache_bytes=0"}));
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("rop.color_cache_bytes is 0"), std::string::npos) << e.what();
  }
}

// The data array is a blackbox to Yosys (`(* blackbox *)`): its instance is no gate and no
// submodule (stat lists no module for it), and adds nothing; any other unknown cell type
// is still an error.
TEST(AreaRopCacheStat, DataArrayBlackboxAddsNoGate) {
  const nlohmann::json stat = nlohmann::json::parse(R"({
    "modules": {
      "\\rast_rop_cache": {"num_cells_by_type": {"$_AND_": 2, "$_DFF_P_": 3, "rast_rop_cache_data": 1},
                            "estimated_num_transistors": "54+"}
    }})");
  const AreaReport r = area_from_yosys_stat(stat, "rast_rop_cache");
  EXPECT_EQ(r.total.cells, 5u);
  EXPECT_EQ(r.total.flip_flops, 3u);
  EXPECT_EQ(r.total.transistors, 54u);
  const nlohmann::json other = nlohmann::json::parse(R"({
    "modules": {"\\top": {"num_cells_by_type": {"$_AND_": 1, "some_macro": 1}, "estimated_num_transistors": "6+"}}})");
  EXPECT_THROW(area_from_yosys_stat(other, "top"), std::runtime_error);
}

// A 512-byte 2-way cache of 16-byte lines over the default 128 x 128 colour surface:
// 16 sets, 32 lines, tags of 16 - 4 - 4 = 8 bits. Flip-flops by hand from the RTL: the
// tag store 32 x (8 tag + 1 rank + valid + dirty) = 352; the request and response
// registers at most 120 (state 4, or 9 one-hot; op 2, address 16, enables 4, word 32,
// way 1, hit and victim flags 3, victim address 16, read word 32, flush scan 4 + 1).
// The data, 512 x 8 = 4,096 bits, is no flip-flop: the storage row, SRAM at 4,096 bits,
// 6 transistors a bit + 10 %: 24,576 + 2,457 = 27,033.
TEST(AreaRopCache, TagsSynthesisedDataCounted) {
  try {
    find_yosys();
  } catch (const std::exception&) {
    GTEST_SKIP() << "yosys not installed";
  }
  const std::filesystem::path stats =
      std::filesystem::temp_directory_path() / ("rastsim_area_rop_cache_" + std::to_string(::getpid()) + ".json");
  ProcessOptions po;
  po.out = Sink::Capture;
  po.err = Sink::Stdout;
  const ProcessResult r = run_process({RASTSIM_BINARY, "area", "--top", "rast_rop_cache", "--no-cache", "-q", "--set",
                                       "rop.color_cache_bytes=512", "--set", "rop.color_cache_ways=2", "--set",
                                       "rop.color_cache_line_bytes=16", "--stats", stats.string()},
                                      po);
  ASSERT_TRUE(WIFEXITED(r.status) && WEXITSTATUS(r.status) == 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
  std::filesystem::remove(stats);
  EXPECT_EQ(j["parameters"]["CacheBytes"], 512);
  EXPECT_EQ(j["parameters"]["AddrW"], 16);
  const uint64_t ff = j["flip_flops"].get<uint64_t>();
  EXPECT_GE(ff, 352u);
  EXPECT_LE(ff, 352u + 120u);
  ASSERT_EQ(j["storage"].size(), 1u);
  EXPECT_EQ(j["storage"][0]["name"], "rop_color_cache.data");
  EXPECT_EQ(j["storage"][0]["bits"], 4096);
  EXPECT_EQ(j["storage"][0]["transistors"], 27033);
  EXPECT_GT(j["transistors"].get<uint64_t>(), 27033u);  // the synthesised logic on top
}

}  // namespace
}  // namespace rastsim
