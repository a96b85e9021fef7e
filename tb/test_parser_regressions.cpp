// SPDX-License-Identifier: Apache-2.0
// The fuzz inputs through the fuzz harnesses (fuzz/harness.h), built by gcc like every
// other test: each file of fuzz/regressions/<target>/ (an input a libFuzzer run once
// crashed, hung or broke an invariant with, docs/fuzzing.md) and of the seed corpus
// fuzz/corpus/<target>/ must end in the parser's documented error or in a result that
// respects the invariants. A crash kills the test, a hang trips ctest's timeout.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/video_timing.h"
#include "display/dac.h"
#include "display/signal_reader.h"
#include "fuzz_common.h"
#include "harness.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename() != "README.md") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Runs every file of `dir`'s <target> subdirectories through its harness; returns how many.
int replay(const fs::path& dir) {
  int n = 0;
  for (const char* target : {"trace", "obj", "mtl", "config", "signal"}) {
    const fuzz::Harness run = fuzz::harness(target);
    for (const fs::path& f : files_in(dir / target)) {
      SCOPED_TRACE(f.string());
      ++n;
      try {
        run(bytes_of(f));
      } catch (const fuzz::Finding& e) {
        ADD_FAILURE() << target << ": " << f.string() << ": " << e.what;
      }
    }
  }
  return n;
}

const fs::path kFuzz = fs::path(RASTSIM_SOURCE_DIR) / "fuzz";

TEST(ParserRegressions, EveryFuzzFindingStaysFixed) {
  // Findings are committed with their fix; the directory is never empty once one is.
  EXPECT_GT(replay(kFuzz / "regressions"), 0);
}

TEST(ParserRegressions, EverySeedPassesTheHarness) { EXPECT_GT(replay(kFuzz / "corpus"), 20); }

// The harness itself can fail: an invariant it checks, broken on purpose, is a Finding.
TEST(ParserRegressions, HarnessReportsABrokenInvariant) {
  EXPECT_THROW(fuzz::check(false, "on purpose"), fuzz::Finding);
  EXPECT_THROW(fuzz::expect_only<std::invalid_argument>("invalid_argument", [] { throw std::out_of_range("x"); }),
               fuzz::Finding);
  EXPECT_NO_THROW(fuzz::expect_only<std::invalid_argument>("invalid_argument",
                                                            [] { throw std::invalid_argument("x"); }));
}

// ---- Found while writing the signal harness (reading the code, not by a fuzzer run) ----

// A VCD of the default config's panel timing (1.3056 MHz: 765.9 ns a pixel clock) with
// codes only; `code_r` declared `width` bits and set to `value`, one pixel clock long.
SignalReadInfo read_codes(const std::string& width, const std::string& value, std::vector<VideoSample>& got) {
  const Config cfg;
  const VideoTiming t = video_timing_from_config(cfg);
  const Dac dac(dac_config_from_config(cfg));
  std::istringstream in("$timescale 1ns $end\n"
                        "$scope module m $end\n"
                        "$var wire 1 h hsync $end\n$var wire 1 v vsync $end\n$var wire 1 k blank $end\n"
                        "$var wire " + width + " R code_r $end\n"
                        "$var wire 8 G code_g $end\n$var wire 8 B code_b $end\n"
                        "$upscope $end\n$enddefinitions $end\n"
                        "#0\n0h\n0v\n0k\nb" + value + " R\nb0 G\nb0 B\n#1000\n");
  return read_video_vcd(in, "wide.vcd", t, dac, [&](const VideoSample& s) { got.push_back(s); });
}

// A code wider than 64 bits with a 1 above bit 63 is over range: clamped to the DAC's
// largest code (8 bits: 255) and reported. It used to lose its high bits and read as 0.
TEST(SignalReaderRegressions, CodeWiderThan64BitsSaturates) {
  std::vector<VideoSample> got;
  const SignalReadInfo info = read_codes("70", "1" + std::string(69, '0'), got);
  ASSERT_EQ(got.size(), 1u);  // sample 0 at 383 ns < 1000 ns; sample 1 at 1149 ns is not
  EXPECT_EQ(got[0].code[0], 255);
  bool reported = false;
  for (const auto& p : info.problems) reported |= p.find("codes above the DAC's 255") != std::string::npos;
  EXPECT_TRUE(reported);
}

// A 64-bit code keeps its value (here 2^63: over range too, but by its own value).
TEST(SignalReaderRegressions, SixtyFourBitCodeIsRead) {
  std::vector<VideoSample> got;
  read_codes("64", "1" + std::string(63, '0'), got);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].code[0], 255);
  got.clear();
  read_codes("64", std::string(56, '0') + "00000101", got);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].code[0], 5);
}

// A $var width beyond int (2^32 + 8) is an error naming the line; it used to wrap to 8.
TEST(SignalReaderRegressions, HugeVarWidthIsAnError) {
  std::vector<VideoSample> got;
  try {
    read_codes("4294967304", "0", got);
    FAIL() << "accepted a width of 2^32 + 8";
  } catch (const SignalFileError& e) {
    EXPECT_NE(std::string(e.what()).find("wide.vcd:6: $var: width '4294967304'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim
