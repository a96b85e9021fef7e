// SPDX-License-Identifier: Apache-2.0
// Arcs (ref/2d/circle_raster.h: arc_outline) against an independent angle test in long
// double, a hand-worked quarter of r = 3, the full circle, and complementary arcs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "ref/2d/circle_raster.h"

namespace rastsim {
namespace {

using Px = std::pair<int, int>;

TEST(ArcRaster, HandWorkedQuarterOfRadius3) {
  // r = 3 outline (docs/2d-shapes.md): (0,+-3), (+-3,0), (+-1,+-3), (+-3,+-1), (+-2,+-2).
  // 0..90 degrees counter-clockwise on screen is the upper-right quarter: x >= 0, y <= 0.
  const auto a = arc_outline(10, 20, 3, 0, 90);
  const std::set<Px> got(a.begin(), a.end());
  const std::set<Px> want{{13, 20}, {13, 19}, {12, 18}, {11, 17}, {10, 17}};
  EXPECT_EQ(got, want);
}

TEST(ArcRaster, FullTurnIsTheCircle) {
  for (int r : {0, 1, 5, 17, 100}) {
    EXPECT_EQ(arc_outline(0, 0, r, 30, 390), circle_outline(0, 0, r)) << r;
    EXPECT_EQ(arc_outline(0, 0, r, -12.5, 400), circle_outline(0, 0, r)) << r;
  }
}

TEST(ArcRaster, MatchesAngleTestInLongDouble) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> ang(-720, 720), sw(0, 359.9);
  std::uniform_int_distribution<int> rad(0, 300);
  const long double pi = 3.141592653589793238462643383279502884L;
  uint64_t checked = 0;
  for (int k = 0; k < 400; ++k) {
    const double a0 = std::round(ang(rng) * 8) / 8, a1 = a0 + std::round(sw(rng) * 8) / 8;
    const int r = rad(rng);
    const auto arc = arc_outline(0, 0, r, a0, a1);
    const std::set<Px> got(arc.begin(), arc.end());
    for (const auto& [x, y] : circle_outline(0, 0, r)) {
      if (x == 0 && y == 0) {
        EXPECT_TRUE(got.count({0, 0}));
        continue;
      }
      // Angle counter-clockwise on screen (y down), in degrees, measured from a0 into [0, 360).
      long double t = std::atan2((long double)-y, (long double)x) * 180 / pi - a0;
      t = std::fmod(t, 360.0L);
      if (t < 0) t += 360;
      const long double sweep = a1 - a0;
      // Too close to an end ray for the 2^24 direction to decide: skip.
      if (std::fabs(t) < 1e-4 || std::fabs(t - 360) < 1e-4 || std::fabs(t - sweep) < 1e-4) continue;
      EXPECT_EQ(got.count({x, y}) == 1, t <= sweep) << "arc " << a0 << ".." << a1 << " r " << r << " pixel " << x
                                                    << "," << y << " at " << double(t) << " deg from a0";
      ++checked;
    }
  }
  EXPECT_GT(checked, 50000u);
}

TEST(ArcRaster, ComplementaryArcsCoverTheCircleMeetingOnTheirEnds) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> deg(0, 359);
  for (int k = 0; k < 200; ++k) {
    const int r = 1 + k;
    const double a0 = deg(rng), a1 = a0 + 1 + deg(rng) % 358;
    const auto p = arc_outline(0, 0, r, a0, a1), q = arc_outline(0, 0, r, a1, a0 + 360);
    std::set<Px> both(p.begin(), p.end());
    both.insert(q.begin(), q.end());
    const auto c = circle_outline(0, 0, r);
    EXPECT_EQ(both, std::set<Px>(c.begin(), c.end())) << r;
    // Pixels in both lie exactly on an end ray.
    const auto d0 = arc_direction(a0), d1 = arc_direction(a1);
    const std::set<Px> ps(p.begin(), p.end());
    for (const Px& x : q)
      if (ps.count(x)) {
        const int64_t qx = x.first, qy = -x.second;
        EXPECT_TRUE(d0.first * qy - d0.second * qx == 0 || d1.first * qy - d1.second * qx == 0)
            << "r " << r << " pixel " << x.first << "," << x.second;
      }
  }
}

}  // namespace
}  // namespace rastsim
