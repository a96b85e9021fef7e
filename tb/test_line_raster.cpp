// SPDX-License-Identifier: Apache-2.0
// Line rasterization on pixel indices (ref/2d/line_raster.h) against goldens written
// independently of the incremental code: the pixel of each major-axis step computed
// directly from the exact line in integer arithmetic (round half toward the minor step
// for Bresenham, half away from it for midpoint, half up for the DDA), hand-worked
// lines, and the closed-form count of Bresenham/midpoint tie pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "common/exact_line.h"
#include "ref/2d/line_raster.h"

namespace rastsim {
namespace {

using testing::exact_dda_line;
using testing::exact_index_line;
using testing::floor_div;
using testing::Pixels;

template <class F>
Pixels collect(F&& draw) {
  Pixels p;
  draw([&](int x, int y) { p.emplace_back(x, y); });
  return p;
}

Pixels bres(int x0, int y0, int x1, int y1) {
  return collect([&](auto e) { bresenham_line(x0, y0, x1, y1, e); });
}
Pixels mid(int x0, int y0, int x1, int y1) {
  return collect([&](auto e) { midpoint_line(x0, y0, x1, y1, e); });
}
Pixels dda(int x0, int y0, int x1, int y1, DdaArith a, int f = 16) {
  return collect([&](auto e) { dda_line(x0, y0, x1, y1, a, f, e); });
}

TEST(LineRaster, HandWorkedFirstOctant) {
  // (0,0)-(5,2): P = -1 E, 3 NE, -3 E, 1 NE, -5 E (worked by hand from the notes' P1 = 2dy - dx).
  const Pixels want = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}};
  EXPECT_EQ(bres(0, 0, 5, 2), want);
  EXPECT_EQ(mid(0, 0, 5, 2), want);  // no tie on this line
}

TEST(LineRaster, HandWorkedTieAndReversal) {
  // (0,0)-(2,1): at x = 1 the line is at y = 0.5, exactly between two pixels.
  EXPECT_EQ(bres(0, 0, 2, 1), (Pixels{{0, 0}, {1, 1}, {2, 1}}));  // P1 = 0 -> NE
  EXPECT_EQ(mid(0, 0, 2, 1), (Pixels{{0, 0}, {1, 0}, {2, 1}}));   // d = 0 -> E
  // Drawn the other way the tie breaks towards the other pixel (relative to the direction).
  EXPECT_EQ(bres(2, 1, 0, 0), (Pixels{{2, 1}, {1, 0}, {0, 0}}));
  EXPECT_EQ(mid(2, 1, 0, 0), (Pixels{{2, 1}, {1, 1}, {0, 0}}));
}

TEST(LineRaster, DegenerateLines) {
  EXPECT_EQ(bres(3, 4, 3, 4), (Pixels{{3, 4}}));
  EXPECT_EQ(mid(-2, 7, -2, 4), (Pixels{{-2, 7}, {-2, 6}, {-2, 5}, {-2, 4}}));
  EXPECT_EQ(dda(1, 1, 4, 1, DdaArith::F32), (Pixels{{1, 1}, {2, 1}, {3, 1}, {4, 1}}));
}

TEST(LineRaster, AllOctantsAndDirectionsMatchTheExactRule) {
  std::mt19937_64 rng(20261122);
  for (int i = 0; i < 20000; ++i) {
    const int span = (i % 4 == 0) ? 2000 : 40;
    std::uniform_int_distribution<int> c(-span, span);
    const int x0 = c(rng), y0 = c(rng), x1 = c(rng), y1 = c(rng);
    SCOPED_TRACE(::testing::Message() << "(" << x0 << "," << y0 << ")-(" << x1 << "," << y1 << ")");
    ASSERT_EQ(bres(x0, y0, x1, y1), exact_index_line(x0, y0, x1, y1, true));
    ASSERT_EQ(mid(x0, y0, x1, y1), exact_index_line(x0, y0, x1, y1, false));
  }
}

TEST(LineRaster, BresenhamMidpointDifferExactlyAtTheClosedFormTieCount) {
  std::mt19937_64 rng(7);
  int64_t lines_with_ties = 0;
  for (int i = 0; i < 20000; ++i) {
    std::uniform_int_distribution<int> c(-60, 60);
    const int x0 = c(rng), y0 = c(rng), x1 = c(rng), y1 = c(rng);
    const Pixels b = bres(x0, y0, x1, y1), m = mid(x0, y0, x1, y1);
    ASSERT_EQ(b.size(), m.size());
    int64_t differ = 0;
    for (size_t k = 0; k < b.size(); ++k) differ += b[k] != m[k];
    const int64_t dx = std::llabs(x1 - x0), dy = std::llabs(y1 - y0);
    ASSERT_EQ(differ, bresenham_midpoint_ties(std::max(dx, dy), std::min(dx, dy)))
        << "(" << x0 << "," << y0 << ")-(" << x1 << "," << y1 << ")";
    lines_with_ties += differ > 0;
  }
  EXPECT_GT(lines_with_ties, 1000);  // the property is exercised, not vacuous
}

TEST(LineRaster, DdaIsExactWhereItsArithmeticIs) {
  // |d_major| a power of two <= 2^10 and coordinates below 2^12: m and every partial sum
  // are exact in f32, f64 and 16-bit fixed point, so the DDA equals the exact rule.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> c(-2000, 2000), e(0, 10), dm(-1024, 1024);
  for (int i = 0; i < 5000; ++i) {
    const int n = 1 << e(rng), d = dm(rng) % (n + 1), x0 = c(rng), y0 = c(rng);
    const bool xmaj = i % 2;
    const int sign = (i % 4 < 2) ? 1 : -1;
    const int x1 = xmaj ? x0 + sign * n : x0 + d, y1 = xmaj ? y0 + d : y0 + sign * n;
    const Pixels want = exact_dda_line(x0, y0, x1, y1);
    ASSERT_EQ(dda(x0, y0, x1, y1, DdaArith::F32), want);
    ASSERT_EQ(dda(x0, y0, x1, y1, DdaArith::F64), want);
    ASSERT_EQ(dda(x0, y0, x1, y1, DdaArith::Fixed, 16), want);
  }
}

TEST(LineRaster, DdaDriftIsFoundWhereTheArithmeticIsNotExact) {
  // The search the stability study runs: the shortest line (from the origin, slopes
  // k/n) whose f32 / 8-bit fixed DDA differs from the exact rule. Both must exist:
  // the test fails if the inexact arithmetics were never inexact.
  auto shortest = [](DdaArith a, int f) {
    for (int n = 1; n <= 4096; ++n)
      for (int d = 0; d <= n; ++d)
        if (dda(0, 0, n, d, a, f) != exact_dda_line(0, 0, n, d)) return n;
    return 0;
  };
  const int f32 = shortest(DdaArith::F32, 0), fixed8 = shortest(DdaArith::Fixed, 8);
  EXPECT_GT(f32, 1);
  EXPECT_GT(fixed8, 1);
  EXPECT_LT(fixed8, f32);  // 8 fraction bits drift long before f32's 24-bit mantissa
  RecordProperty("shortest_f32_dda_error", f32);
  RecordProperty("shortest_fixed8_dda_error", fixed8);
  std::printf("shortest line where the DDA differs from the exact rule: f32 %d px, fixed (8 bits) %d px\n", f32,
              fixed8);
}

// Endpoint order (the notes' "left to right or right to left"): how many random lines
// change pixels when drawn reversed. Bresenham and midpoint change exactly the lines
// with a tie (a tie breaks relative to the drawing direction); the figures printed
// here are the ones docs/2d-lines.md quotes.
TEST(LineRaster, ReversalChangesExactlyTheTieLines) {
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<int> c(-100, 100);
  const int n = 20000;
  int changed[5] = {}, tie_lines = 0;
  auto set_of = [](Pixels p) {
    std::sort(p.begin(), p.end());
    return p;
  };
  for (int i = 0; i < n; ++i) {
    const int x0 = c(rng), y0 = c(rng), x1 = c(rng), y1 = c(rng);
    const int64_t dx = std::llabs(x1 - x0), dy = std::llabs(y1 - y0);
    const bool tie = bresenham_midpoint_ties(std::max(dx, dy), std::min(dx, dy)) > 0;
    tie_lines += tie;
    const bool b = set_of(bres(x0, y0, x1, y1)) != set_of(bres(x1, y1, x0, y0));
    const bool m = set_of(mid(x0, y0, x1, y1)) != set_of(mid(x1, y1, x0, y0));
    ASSERT_EQ(b, tie);
    ASSERT_EQ(m, tie);
    changed[0] += b;
    changed[1] += m;
    const DdaArith arith[3] = {DdaArith::F32, DdaArith::F64, DdaArith::Fixed};
    for (int a = 0; a < 3; ++a)
      changed[2 + a] += set_of(dda(x0, y0, x1, y1, arith[a])) != set_of(dda(x1, y1, x0, y0, arith[a]));
  }
  std::printf("%d random lines, endpoints in [-100, 100]^2: %d with Bresenham/midpoint ties; changed by reversal: "
              "bresenham %d, midpoint %d, dda f32 %d, dda f64 %d, dda fixed (16 bits) %d\n",
              n, tie_lines, changed[0], changed[1], changed[2], changed[3], changed[4]);
}

}  // namespace
}  // namespace rastsim

namespace rastsim {
namespace {

// ---- The diamond-exit rule, by brute force ----
// Written without clipping: on the segment, membership in the test area can change
// only where the segment crosses one of the diamond's four edge lines, so it is
// enough to test t = 0, every crossing in [0, 1] and the midpoints between them.
struct Q {  // rational num / den, den > 0
  i128 num, den;
};
bool in_area_q(const i128 u, const i128 v, const i128 den, const i128 h, bool y_major) {
  const i128 au = u < 0 ? -u : u, av = v < 0 ? -v : v;
  return au + av < h * den || (au + av == h * den && v > 0) || (y_major && u == h * den && v == 0);
}
bool lit_brute(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t px, int64_t py, int f) {
  const i128 h = i128(1) << f, cx = (2 * i128(px) + 1) * h, cy = (2 * i128(py) + 1) * h;
  const i128 ax = 2 * i128(x0) - cx, ay = 2 * i128(y0) - cy, dx = 2 * (i128(x1) - x0), dy = 2 * (i128(y1) - y0);
  const bool ymaj = (dx < 0 ? -dx : dx) < (dy < 0 ? -dy : dy);
  auto in_at = [&](const Q& t) { return in_area_q(ax * t.den + dx * t.num, ay * t.den + dy * t.num, t.den, h, ymaj); };
  if (in_at({1, 1})) return false;
  std::vector<Q> ts = {{0, 1}, {1, 1}};
  for (int su : {-1, 1})
    for (int sv : {-1, 1}) {  // su u + sv v = h  =>  t = (h - su ax - sv ay) / (su dx + sv dy)
      i128 p = su * dx + sv * dy, q = h - su * ax - sv * ay;
      if (p == 0) continue;
      if (p < 0) p = -p, q = -q;
      if (q >= 0 && q <= p) ts.push_back({q, p});
    }
  std::sort(ts.begin(), ts.end(), [](const Q& a, const Q& b) { return a.num * b.den < b.num * a.den; });
  for (size_t i = 0; i < ts.size(); ++i) {
    if (in_at(ts[i])) return true;
    if (i + 1 < ts.size() && in_at({ts[i].num * ts[i + 1].den + ts[i + 1].num * ts[i].den, 2 * ts[i].den * ts[i + 1].den}))
      return true;
  }
  return false;
}

std::set<std::pair<int, int>> diamond_set(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int f) {
  std::set<std::pair<int, int>> s;
  diamond_line(x0, y0, x1, y1, f, [&](int x, int y) { EXPECT_TRUE(s.insert({x, y}).second) << "pixel twice"; });
  return s;
}

TEST(DiamondLine, MatchesBruteForce) {
  std::mt19937_64 rng(31);
  for (int i = 0; i < 4000; ++i) {
    const int f = (i % 2) ? 2 : 4;
    std::uniform_int_distribution<int64_t> c(0, int64_t{12} << f);
    int64_t x0 = c(rng), y0 = c(rng), x1 = c(rng), y1 = c(rng);
    if (i % 3 == 0) {  // centres, corners, 45-degree and axis-aligned lines
      x0 = (x0 >> (f - 1)) << (f - 1), y0 = (y0 >> (f - 1)) << (f - 1);
      x1 = (x1 >> (f - 1)) << (f - 1), y1 = (i % 6 == 0) ? y0 + (x1 - x0) : ((y1 >> (f - 1)) << (f - 1));
    }
    const auto got = diamond_set(x0, y0, x1, y1, f);
    std::set<std::pair<int, int>> want;
    for (int64_t py = (std::min(y0, y1) >> f) - 2; py <= (std::max(y0, y1) >> f) + 2; ++py)
      for (int64_t px = (std::min(x0, x1) >> f) - 2; px <= (std::max(x0, x1) >> f) + 2; ++px)
        if (lit_brute(x0, y0, x1, y1, px, py, f)) want.insert({int(px), int(py)});
    ASSERT_EQ(got, want) << "(" << x0 << "," << y0 << ")-(" << x1 << "," << y1 << ") F " << f;
  }
}

TEST(DiamondLine, HandWorked) {
  const int f = 4;  // 16 = 1 px
  // Centre of pixel 0 to the centre of pixel 4 on row 0: it exits diamonds 0..3 and ends
  // inside diamond 4, which it does not light.
  EXPECT_EQ(diamond_set(8, 8, 4 * 16 + 8, 8, f), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // A strip through that point lights pixel 4 exactly once (with the next segment).
  EXPECT_EQ(diamond_set(4 * 16 + 8, 8, 6 * 16 + 8, 8, f), (std::set<std::pair<int, int>>{{4, 0}, {5, 0}}));
  // A horizontal line along row boundary y = 1 (between rows 0 and 1) touches the
  // bottom corners of row 0 (in) and the top corners of row 1 (out): row 0 lights.
  EXPECT_EQ(diamond_set(8, 16, 3 * 16 + 8, 16, f), (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}}));
  // A zero-length line lights nothing.
  EXPECT_TRUE(diamond_set(40, 40, 40, 40, f).empty());
}

}  // namespace
}  // namespace rastsim
