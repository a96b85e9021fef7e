// SPDX-License-Identifier: Apache-2.0
// The 2D engine RTL (rtl/rast_engine2d.sv with its line unit, pattern and ROP3) in the
// co-simulation, through `rastsim cosim`: random 2D scenes mixed with triangles (lines
// in every octant and direction through the line unit, overlapping blits in all four
// directions), and all 256 ROP3 codes on random data. Each run: zero mismatches, the
// testbench framebuffer's CRC equal to the reference model's, and the SystemC model's
// cycle count within 2 % of the RTL's (--max-error 0.02). memory.model = fixed, and with
// the diamond method each random scene again with the config's DRAM model.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/random_2d_trace.h"
#include "util/process.h"

namespace {

// Runs `rastsim cosim` on a trace text with extra --set options; returns its stats JSON.
nlohmann::json cosim(const std::string& trace, const std::string& name, const std::string& sets) {
  const auto dir = std::filesystem::temp_directory_path() / ("rastsim_cosim_2d_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto trace_path = dir / (name + ".trace"), stats_path = dir / (name + ".json");
  std::ofstream(trace_path) << trace;
  // memory.model = fixed: the 2D engine's cycles without DRAM stalls (the test card with
  // dram: the ctest cosim.dram.2d.test_card; docs/memory.md "RTL co-simulation").
  std::vector<std::string> argv{RASTSIM_BINARY, "cosim", "--config", std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml",
                                "--set", "memory.model=fixed", "--scene", trace_path.string(), "--stats",
                                stats_path.string(), "--max-error", "0.02"};
  std::istringstream words(sets);  // " --set K=V ..." (no value holds a space)
  for (std::string w; words >> w;) argv.push_back(w);
  rastsim::ProcessOptions o;
  o.out = rastsim::Sink::Capture;
  o.err = rastsim::Sink::Stdout;
  const rastsim::ProcessResult r = rastsim::run_process(argv, o);
  std::string cmd;
  for (const std::string& a : argv) cmd += a + " ";
  EXPECT_TRUE(r.ok()) << cmd << "\n" << r.out << "\ntrace kept at " << trace_path;
  nlohmann::json j;
  std::ifstream in(stats_path);
  if (in) in >> j;
  if (r.ok()) std::filesystem::remove_all(dir);
  return j;
}

void expect_exact(const nlohmann::json& j) {
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["mismatches"], 0) << j["first_mismatch"];
  EXPECT_EQ(j["framebuffer_crc32_rtl"], j["framebuffer_crc32_ref"]);
  EXPECT_GT(j["pixels_2d"].get<uint64_t>(), 0u);
}

class Cosim2d : public ::testing::TestWithParam<std::string> {};

TEST_P(Cosim2d, RandomMixedScenesMatchReferenceAndSystemC) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::string sets = " --set line.method=" + GetParam() + " --set display.width=96 --set display.height=80";
    if (seed == 2) sets += " --set fifo.op2d_depth=1 --set fifo.draw2d_depth=1 --set engine2d.fill_pixels_per_cycle=3";
    if (seed == 3) sets += " --set engine2d.span_setup_cycles=0 --set engine2d.rmw_cycles=3 --set "
                           "engine2d.blit_bytes_per_cycle=3";
    const auto j = cosim(rastsim::testing::random_2d_trace(seed * 7919, 96, 80, 80),
                         GetParam() + "_" + std::to_string(seed), sets);
    expect_exact(j);
    if (!j.is_object()) continue;
    std::cout << GetParam() << " seed " << seed << ": " << j["pixels_2d"] << " 2D pixels, cycles_rtl "
              << j["cycles_rtl"] << ", cycles_model " << j["cycles_model"] << "\n";
    if (GetParam() != "diamond") continue;
    // The config's DRAM model (a later --set wins): the 2D engine's memory port waits for
    // each operation's fills; exact, SystemC within 2 % (cosim's --max-error).
    const auto d = cosim(rastsim::testing::random_2d_trace(seed * 7919, 96, 80, 80),
                         GetParam() + "_dram_" + std::to_string(seed), sets + " --set memory.model=dram");
    expect_exact(d);
    if (!d.is_object()) continue;
    EXPECT_GT(d["cycles_rtl"].get<uint64_t>(), j["cycles_rtl"].get<uint64_t>()) << "the fills cost cycles";
    std::cout << "  dram: cycles_rtl " << d["cycles_rtl"] << ", cycles_model " << d["cycles_model"] << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(LineMethods, Cosim2d, ::testing::Values("diamond", "bresenham", "midpoint", "dda"));

// Codes that read no S move 4 or 8 bytes a pixel: at 8 bytes a cycle the blitter still
// moves at most one pixel a cycle, and its byte credit must not wrap on a long row
// (250 pixels: an unsaturated 8-bit credit growing 4 a cycle would wrap after 64).
TEST(Cosim2dBlit, CodesWithoutSourceMoveAPixelACycle) {
  for (const char* code : {"00", "F0", "55", "5A"}) {
    SCOPED_TRACE(code);
    const std::string t = std::string("viewport 254 32\nclear 1 2 3\ncolor 9 8 7\nrect 0 0 254 8\nrop3 ") + code +
                          "\nblit 0 0 2 10 250 3\n";
    const auto j = cosim(t, std::string("blit_") + code, " --set display.width=254 --set display.height=32 --set "
                                                         "engine2d.blit_bytes_per_cycle=8");
    expect_exact(j);
    // The scene's one clear: the RTL ROP takes its marker in a cycle before the
    // rop_clear_cycles fill writes (docs/rtl.md "ROP", Markers); the model charges the writes.
    EXPECT_EQ(j["cycles_model"].get<uint64_t>() + 1, j["cycles_rtl"].get<uint64_t>());
  }
}

// Every ROP3 code through a blit into its own 4x4 cell (so every result stays visible),
// over random triangles and rectangles; then the 16 codes without S as fills.
TEST(Cosim2dRop3, All256CodesOnRandomData) {
  std::mt19937_64 rng(256);
  auto ri = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  std::string t = "viewport 128 128\nclear 10 20 30\n";
  for (int i = 0; i < 40; ++i) {
    t += "color " + std::to_string(ri(0, 255)) + " " + std::to_string(ri(0, 255)) + " " + std::to_string(ri(0, 255)) +
         "\nrect " + std::to_string(ri(0, 120)) + " " + std::to_string(ri(0, 120)) + " " + std::to_string(ri(1, 30)) +
         " " + std::to_string(ri(1, 30)) + "\n";
  }
  t += "pattern 0F1E3C78F0E1C387\nbgcolor 200 100 50\ncolor 60 70 80\n";
  const char* hex = "0123456789ABCDEF";
  for (int code = 0; code < 256; ++code) {
    t += std::string("rop3 ") + hex[code >> 4] + hex[code & 15] + "\n";
    t += "blit " + std::to_string(ri(0, 124)) + " " + std::to_string(ri(0, 124)) + " " + std::to_string(code % 32 * 4) +
         " " + std::to_string(code / 32 * 4) + " 4 4\n";
  }
  int fills = 0;
  for (int code = 0; code < 256; ++code) {
    if (rastsim::rop3_reads_source(uint8_t(code))) continue;
    t += std::string("rop3 ") + hex[code >> 4] + hex[code & 15] + "\nrect " + std::to_string(fills * 8) +
         " 40 8 8\n";
    ++fills;
  }
  EXPECT_EQ(fills, 16);
  expect_exact(cosim(t, "rop3_all", ""));
}

}  // namespace
