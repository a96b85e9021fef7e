// SPDX-License-Identifier: Apache-2.0
// Midpoint circles (ref/2d/circle_raster.h) against the notes' decision evaluated directly
// from F(x, y) = x^2 + y^2 - r^2 at every step (not incrementally), for radii 0..2000;
// hand-worked small radii; each outline pixel once; eight-way symmetry; filled rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "ref/2d/circle_raster.h"

namespace rastsim {
namespace {

// The octant by the definition: at (x, y), SE when F(x + 1, y - 1/2) >= 0, evaluated
// as 4F = 4(x + 1)^2 + (2y - 1)^2 - 4r^2 from scratch every step.
std::vector<std::pair<int64_t, int64_t>> octant_by_definition(int64_t r) {
  std::vector<std::pair<int64_t, int64_t>> pts{{0, r}};
  for (int64_t x = 0, y = r; x < y;) {
    const int64_t f4 = 4 * (x + 1) * (x + 1) + (2 * y - 1) * (2 * y - 1) - 4 * r * r;
    if (f4 >= 0) --y;
    ++x;
    pts.emplace_back(x, y);
  }
  return pts;
}

TEST(CircleRaster, OctantMatchesTheDirectDecisionForRadii0To2000) {
  for (int64_t r = 0; r <= 2000; ++r) ASSERT_EQ(midpoint_circle_octant(r), octant_by_definition(r)) << "r = " << r;
}

TEST(CircleRaster, HandWorkedRadii) {
  // r = 0: the centre only. r = 1: the four axis neighbours (d0 = 1/4 >= 0 -> SE to (1, 0)).
  EXPECT_EQ(circle_outline(5, 5, 0), (std::vector<std::pair<int, int>>{{5, 5}}));
  EXPECT_EQ(circle_outline(0, 0, 1), (std::vector<std::pair<int, int>>{{0, -1}, {-1, 0}, {1, 0}, {0, 1}}));
  // r = 3 by hand: d0 = 5/4 - 3 < 0 -> E (1, 3), d = -7/4 + 3 = 5/4 >= 0 -> SE (2, 2); stop.
  EXPECT_EQ(midpoint_circle_octant(3), (std::vector<std::pair<int64_t, int64_t>>{{0, 3}, {1, 3}, {2, 2}}));
  EXPECT_EQ(circle_outline(0, 0, 3).size(), 16u);  // 4 axis + 8 (1,3)-type + 4 diagonal
}

TEST(CircleRaster, OutlineEachPixelOnceSymmetricAndNearTheCircle) {
  for (int r : {0, 1, 2, 3, 7, 10, 31, 100, 257, 1000, 2000}) {
    SCOPED_TRACE(r);
    const auto px = circle_outline(-3, 4, r);
    const std::set<std::pair<int, int>> set(px.begin(), px.end());
    ASSERT_EQ(set.size(), px.size());  // each pixel once
    for (const auto& [x, y] : px) {
      const int64_t dx = x + 3, dy = y - 4;
      ASSERT_TRUE(set.count({int(-3 - dx), y}) && set.count({x, int(4 - dy)}) && set.count({int(-3 + dy), int(4 + dx)}));
      // The midpoint walk stays within half a pixel of the circle along its minor axis:
      // |x^2 + y^2 - r^2| <= max(|x|, |y|) + 1/4 (so 4|F| <= 4 max + 1).
      const int64_t f = dx * dx + dy * dy - int64_t(r) * r;
      ASSERT_LE(4 * std::abs(f), 4 * std::max(std::abs(dx), std::abs(dy)) + 1) << x << "," << y;
    }
  }
}

TEST(CircleRaster, FillRowsAreBoundedByTheOutline) {
  for (int r : {0, 1, 5, 64, 333}) {
    const auto outline = circle_outline(10, -2, r);
    const auto spans = circle_fill(10, -2, r);
    ASSERT_EQ(spans.size(), size_t(2 * r + 1));
    int64_t area = 0;
    for (const auto& s : spans) {
      std::vector<int> xs;
      for (const auto& [x, y] : outline)
        if (y == s.y) xs.push_back(x);
      ASSERT_FALSE(xs.empty());
      EXPECT_EQ(s.x0, *std::min_element(xs.begin(), xs.end()));
      EXPECT_EQ(s.x1, *std::max_element(xs.begin(), xs.end()) + 1);
      area += s.x1 - s.x0;
    }
    // Roughly pi r^2 (the outline adds about 4r pixels of rim).
    if (r >= 64) {
      EXPECT_NEAR(double(area), 3.14159 * r * r, 4.5 * r);
    }
  }
}

}  // namespace
}  // namespace rastsim
