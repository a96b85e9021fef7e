// SPDX-License-Identifier: Apache-2.0
// `rastsim area --top rast_hiz` / `rast_hiz_test` build hierarchical Z's units with the
// config's HizRtlParams (rtlsim/rtl_params.h root_rtl_params; docs/rtl.md "Hi-Z"): Blocks
// is the reference's on-chip count, and a config without an on-chip table is refused.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common.h"
#include "rtlsim/rtl_params.h"

namespace rastsim {
namespace {

ArchParams hiz_arch(const std::vector<std::string>& sets) {
  app::ConfigOptions c;
  c.sets = sets;
  return ArchParams::resolve(app::load_config(c));
}

// By hand, the default config (128 x 128, 24-bit depth, s7.16, 16 px tiles, 4 ROP lanes):
// max, 8 px blocks: an entry 2 x 24 + 64 = 112 bits -> 14 -> 16 bytes, 16384 / 16 = 1024 >=
// the 16 x 16 = 256 blocks: 256 on chip. minmax, 4 px: 4 x 24 + 16 = 112 bits, 16 bytes,
// 1024 blocks, all on chip at 16384 bytes and 256 of them at 4096.
TEST(AreaHizParams, FromTheConfig) {
  using P = std::vector<std::pair<std::string, int>>;
  EXPECT_EQ(root_rtl_params("rast_hiz", hiz_arch({"depth.hiz=max"})),
            (P{{"DepthW", 24}, {"PixelW", 14}, {"BlockLog2", 3}, {"MinMax", 0}, {"Blocks", 256},
               {"TileLog2Max", 4}, {"Lanes", 4}}));
  EXPECT_EQ(root_rtl_params("rast_hiz", hiz_arch({"depth.hiz=minmax", "depth.hiz_block=4"}))[4],
            (std::pair<std::string, int>{"Blocks", 1024}));
  EXPECT_EQ(root_rtl_params("rast_hiz",
                            hiz_arch({"depth.hiz=minmax", "depth.hiz_block=4", "depth.hiz_bytes=4096"}))[4],
            (std::pair<std::string, int>{"Blocks", 256}));
  EXPECT_EQ(root_rtl_params("rast_hiz_test", hiz_arch({"depth.hiz=max"})),
            (P{{"CoordW", 24}, {"CoordFrac", 16}, {"CoefW", 25}, {"EdgeW", 49}, {"AreaW", 48}, {"DepthW", 24},
               {"PixelW", 14}}));
  EXPECT_THROW(root_rtl_params("rast_hiz", hiz_arch({})), std::runtime_error);  // depth.hiz = off
  EXPECT_THROW(root_rtl_params("rast_hiz", hiz_arch({"depth.hiz=max", "depth.hiz_bytes=8"})), std::runtime_error);
}

}  // namespace
}  // namespace rastsim
