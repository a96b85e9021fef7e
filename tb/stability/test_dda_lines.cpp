// SPDX-License-Identifier: Apache-2.0
// DDA lines (docs/stability.md, "DDA lines"): the shortest line at which the f32, f64 and
// fixed-point DDA (ref/2d/line_raster.h) first differ from the exact rule.
//
// Search space: every line from the origin (0, 0) to (n, d), 0 <= d <= n (the first
// octant, x-major, diagonal included), by increasing major length n = 1, 2, ... up to a
// cap; within one n by increasing d. "Shortest" = the smallest n for which some d lights
// a pixel other than the exact DDA's floor(k d / n + 1/2) (tb/common/exact_line.h,
// integers). Two figures an arithmetic: the first difference of any kind (at a tie, where
// the exact value is k + 1/2 and a rounded slope that lands below it flips the pixel),
// and the first difference off a tie (accumulated error larger than the distance to the
// rounding boundary: real drift).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "common/exact_line.h"
#include "ref/2d/line_raster.h"
#include "stability/doc_table.h"

namespace rastsim {
namespace {

constexpr int kDefaultFracBits = 16;  // F of configs/default.toml's s7.16 (line.dda_arith = fixed uses it)

struct Found { int n = 0, d = 0; };

// The first (n, d) whose DDA differs from the exact rule, at any pixel or (off_tie) at a
// pixel that is not an exact tie; n = 0 when none up to `cap`.
Found shortest_difference(DdaArith arith, int frac_bits, int cap, bool off_tie) {
  for (int n = 1; n <= cap; ++n)
    for (int d = 0; d <= n; ++d) {
      int64_t k = 0;
      bool differs = false;
      dda_line(0, 0, n, d, arith, frac_bits, [&](int x, int y) {
        const bool tie = testing::exact_dda_tie(n, d, k);
        const int64_t want = testing::floor_div(2 * k * d + n, 2 * n);
        if ((x != k || y != want) && !(off_tie && tie)) differs = true;
        ++k;
      });
      if (differs) return {n, d};
    }
  return {};
}

std::string describe(Found f, int cap) {
  return f.n ? std::to_string(f.n) + " (d = " + std::to_string(f.d) + ")" : "none up to " + std::to_string(cap);
}

// The search cap: kept small enough for ctest; RASTSIM_STABILITY_LINE_CAP raises it for the
// longer run the doc quotes (the f64 drift search is cubic in the cap).
int line_cap() {
  const char* e = std::getenv("RASTSIM_STABILITY_LINE_CAP");
  return e ? std::atoi(e) : 1024;
}

struct DdaCase { const char* row; DdaArith arith; int frac_bits; };
void PrintTo(const DdaCase& c, std::ostream* os) { *os << c.row; }

class DdaLines : public ::testing::TestWithParam<DdaCase> {};

TEST_P(DdaLines, ShortestDifferenceMatchesTheDoc) {
  const DdaCase c = GetParam();
  const int cap = line_cap();
  const Found any = shortest_difference(c.arith, c.frac_bits, cap, false);
  const Found drift = shortest_difference(c.arith, c.frac_bits, cap, true);
  std::printf("| %s | %s | %s |\n", c.row, describe(any, cap).c_str(), describe(drift, cap).c_str());
  const testing::DocRow row = testing::doc_row("DDA lines", c.row);
  ASSERT_GE(row.size(), 3u);
  // The doc's figures are those of the default cap; a longer run only prints.
  if (cap != 1024) GTEST_SKIP() << "RASTSIM_STABILITY_LINE_CAP set: figures printed, not compared";
  EXPECT_EQ(describe(any, cap), row[1]) << "the figure moved: update docs/stability.md and say why";
  EXPECT_EQ(describe(drift, cap), row[2]) << "the figure moved: update docs/stability.md and say why";
}

INSTANTIATE_TEST_SUITE_P(Arith, DdaLines,
                         ::testing::Values(DdaCase{"f32", DdaArith::F32, 0}, DdaCase{"f64", DdaArith::F64, 0},
                                           DdaCase{"fixed 16", DdaArith::Fixed, kDefaultFracBits}),
                         [](const auto& info) {
                           return std::string(info.param.arith == DdaArith::F32   ? "F32"
                                              : info.param.arith == DdaArith::F64 ? "F64"
                                                                                  : "Fixed16");
                         });

// The golden itself: hand-worked tie. (0,0)-(6,5): at k = 3 the exact minor is 2.5, so the
// exact rule lights y = 3; a slope rounded below 5/6 lands under 2.5 and lights y = 2.
TEST(DdaLinesGolden, HandWorkedTie) {
  const testing::Pixels p = testing::exact_dda_line(0, 0, 6, 5);
  EXPECT_EQ(p[3], std::make_pair(3, 3));
  EXPECT_TRUE(testing::exact_dda_tie(6, 5, 3));
  EXPECT_FALSE(testing::exact_dda_tie(6, 5, 2));
}

}  // namespace
}  // namespace rastsim
