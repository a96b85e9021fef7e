// SPDX-License-Identifier: Apache-2.0
// Points (ref/2d/point_raster.h) against a brute-force test of every pixel centre near the
// point (exact integers), hand-worked cases, and tiling: points of size S at S-pixel
// spacing cover every pixel once.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "ref/2d/point_raster.h"

namespace rastsim {
namespace {

// Centre (2p + 1) / 2 inside [x - s/2, x + s/2), all in units of 2^-(F+1) pixel.
bool centre_inside(int64_t p, int64_t x, int size, int f) {
  const int64_t c = (2 * p + 1) << f, lo = 2 * x - (int64_t(size) << f), hi = 2 * x + (int64_t(size) << f);
  return c >= lo && c < hi;
}

TEST(PointRaster, MatchesBruteForce) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20000; ++i) {
    const int f = 1 + int(rng() % 16), size = int(rng() % 9);
    std::uniform_int_distribution<int64_t> c(-(int64_t{40} << f), int64_t{40} << f);
    int64_t x = c(rng), y = c(rng);
    if (i % 3 == 0) x = (x >> f) << f;                             // on a pixel corner
    if (i % 5 == 0) y = ((y >> f) << f) + (int64_t{1} << (f - 1));  // on a pixel centre row
    const PixelRect r = point_pixels(x, y, size, f);
    for (int64_t py = (y >> f) - 6; py <= (y >> f) + 6; ++py)
      for (int64_t px = (x >> f) - 6; px <= (x >> f) + 6; ++px) {
        const bool want = centre_inside(px, x, size, f) && centre_inside(py, y, size, f);
        const bool got = px >= r.x0 && px < r.x1 && py >= r.y0 && py < r.y1;
        ASSERT_EQ(got, want) << "point " << x << "," << y << " size " << size << " F " << f << " pixel " << px
                             << "," << py;
      }
  }
}

TEST(PointRaster, HandWorked) {
  const int f = 4;  // 16 = 1 px
  EXPECT_EQ(point_pixels(5 * 16 + 8, 7 * 16 + 8, 1, f), (PixelRect{5, 7, 6, 8}));  // size 1 at a centre: that pixel
  EXPECT_EQ(point_pixels(5 * 16, 7 * 16, 2, f), (PixelRect{4, 6, 6, 8}));          // size 2 at a corner: 2x2
  // Size 1 at a pixel corner (5, 7): the square [4.5, 5.5) holds centre 4.5 (left edge, in)
  // and not 5.5 (right edge, out).
  EXPECT_EQ(point_pixels(5 * 16, 7 * 16, 1, f), (PixelRect{4, 6, 5, 7}));
  EXPECT_TRUE(point_pixels(0, 0, 0, f).empty());
}

TEST(PointRaster, PointsOnAGridTileThePlaneOnce) {
  for (int size : {1, 2, 3, 4}) {
    std::map<std::pair<int, int>, int> hits;
    for (int gy = 0; gy < 6; ++gy)
      for (int gx = 0; gx < 6; ++gx) {
        const PixelRect r = point_pixels(int64_t(gx * size) * 256 + 37, int64_t(gy * size) * 256 + 91, size, 8);
        for (int y = r.y0; y < r.y1; ++y)
          for (int x = r.x0; x < r.x1; ++x) ++hits[{x, y}];
      }
    EXPECT_EQ(hits.size(), size_t(36 * size * size));
    for (const auto& [p, n] : hits) ASSERT_EQ(n, 1);
  }
}

}  // namespace
}  // namespace rastsim
