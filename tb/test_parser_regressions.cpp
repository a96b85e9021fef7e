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
#include <string>
#include <vector>

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

}  // namespace
}  // namespace rastsim
