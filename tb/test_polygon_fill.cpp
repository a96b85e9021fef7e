// SPDX-License-Identifier: Apache-2.0
// Scanline polygon fill (ref/2d/polygon_fill.h) against a brute-force test of every pixel
// centre (a ray to the left, crossings counted per edge, exact integers) for both
// rules on random simple and self-intersecting polygons; hand-worked shapes; and meshes
// of polygons that tile a rectangle cover every pixel exactly once.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "ref/fixed_point.h"
#include "ref/2d/polygon_fill.h"

namespace rastsim {
namespace {

using Poly = std::vector<std::pair<int64_t, int64_t>>;

// Pixel (px, py) by its centre (2px + 1, 2py + 1) / 2: every edge whose half-open
// y-range [top, bottom) holds the centre's y and whose crossing lies at or left of the
// centre counts (direction +1 downwards); even-odd = odd count, non-zero = sum != 0.
bool inside_brute(const Poly& v, int f, PolygonRule rule, int64_t px, int64_t py) {
  const i128 cx = i128(2 * px + 1) << f, cy = i128(2 * py + 1) << f;  // in units of 2^-(f+1)
  int count = 0, winding = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    i128 x0 = 2 * i128(v[i].first), y0 = 2 * i128(v[i].second);
    i128 x1 = 2 * i128(v[(i + 1) % v.size()].first), y1 = 2 * i128(v[(i + 1) % v.size()].second);
    if (y0 == y1) continue;
    const int dir = y1 > y0 ? 1 : -1;
    if (y0 > y1) {
      std::swap(x0, x1);
      std::swap(y0, y1);
    }
    if (cy < y0 || cy >= y1) continue;
    // crossing x = x0 + (cy - y0)(x1 - x0)/(y1 - y0) <= cx  <=>  (x0 - cx)(y1 - y0) + (cy - y0)(x1 - x0) <= 0
    if ((x0 - cx) * (y1 - y0) + (cy - y0) * (x1 - x0) <= 0) {
      ++count;
      winding += dir;
    }
  }
  return rule == PolygonRule::EvenOdd ? (count % 2 == 1) : (winding != 0);
}

std::set<std::pair<int, int>> pixels_of(const std::vector<PixelSpan>& spans) {
  std::set<std::pair<int, int>> s;
  for (const auto& sp : spans)
    for (int x = sp.x0; x < sp.x1; ++x) EXPECT_TRUE(s.insert({x, sp.y}).second) << "pixel twice";
  return s;
}

TEST(PolygonFill, MatchesBruteForceOnRandomPolygons) {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 3000; ++i) {
    const int f = (i % 3 == 0) ? 1 : 4;
    std::uniform_int_distribution<int64_t> c(0, int64_t{24} << f);
    Poly v(3 + rng() % 7);  // 3..9 vertices: random polygons are mostly self-intersecting
    for (auto& p : v) {
      p = {c(rng), c(rng)};
      if (i % 2) p = {(p.first >> f) << f, (p.second >> f) << f};  // integer vertices: ties on centres and edges
    }
    for (PolygonRule rule : {PolygonRule::EvenOdd, PolygonRule::NonZero}) {
      const auto got = pixels_of(fill_polygon(v, f, rule));
      for (int py = -1; py <= 26; ++py)
        for (int px = -1; px <= 26; ++px)
          ASSERT_EQ(got.count({px, py}) == 1, inside_brute(v, f, rule, px, py))
              << "polygon " << i << " rule " << to_string(rule) << " pixel " << px << "," << py;
    }
  }
}

TEST(PolygonFill, HandWorked) {
  const int f = 4;
  auto px = [](int64_t a) { return a * 16; };
  // A 4x3 rectangle on pixel corners: 12 pixels, rows 0..2, columns 0..3.
  const auto rect = fill_polygon({{px(0), px(0)}, {px(4), px(0)}, {px(4), px(3)}, {px(0), px(3)}}, f, PolygonRule::EvenOdd);
  EXPECT_EQ(rect, (std::vector<PixelSpan>{{0, 0, 4}, {1, 0, 4}, {2, 0, 4}}));
  // A pentagram (self-intersecting): even-odd leaves the centre pentagon empty, non-zero fills it.
  const Poly star = {{px(10), px(0)}, {px(16), px(19)}, {px(0), px(7)}, {px(20), px(7)}, {px(4), px(19)}};
  EXPECT_FALSE(pixels_of(fill_polygon(star, f, PolygonRule::EvenOdd)).count({10, 10}));
  EXPECT_TRUE(pixels_of(fill_polygon(star, f, PolygonRule::NonZero)).count({10, 10}));
  EXPECT_TRUE(fill_polygon({{0, 0}, {px(5), 0}}, f, PolygonRule::EvenOdd).empty());  // degenerate
}

TEST(PolygonFill, SharedEdgeMeshesCoverEveryPixelOnce) {
  // A jittered grid of vertices split into quads (and half of them into two triangles)
  // tiles [0, 40) x [0, 30): every pixel exactly once, both rules, either winding.
  std::mt19937_64 rng(23);
  const int f = 4, n = 5;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::vector<std::pair<int64_t, int64_t>>> g(n + 1, std::vector<std::pair<int64_t, int64_t>>(n + 1));
    std::uniform_int_distribution<int64_t> jit(-24, 24);
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        int64_t x = int64_t(i) * 40 * 16 / n, y = int64_t(j) * 30 * 16 / n;
        if (i > 0 && i < n) x += jit(rng);
        if (j > 0 && j < n) y += jit(rng);
        if (trial % 2) {  // vertices on pixel corners
          x = (x >> 4) << 4;
          y = (y >> 4) << 4;
        }
        g[j][i] = {x, y};
      }
    std::map<std::pair<int, int>, int> hits;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        std::vector<Poly> polys;
        const Poly quad = {g[j][i], g[j][i + 1], g[j + 1][i + 1], g[j + 1][i]};
        if ((i + j) % 2) {
          polys.push_back({quad[0], quad[1], quad[2]});
          polys.push_back({quad[2], quad[3], quad[0]});
        } else {
          polys.push_back(trial % 3 ? quad : Poly{quad[3], quad[2], quad[1], quad[0]});
        }
        for (const Poly& p : polys)
          for (const auto& sp : fill_polygon(p, f, (trial % 2) ? PolygonRule::NonZero : PolygonRule::EvenOdd))
            for (int x = sp.x0; x < sp.x1; ++x) ++hits[{x, sp.y}];
      }
    ASSERT_EQ(hits.size(), 40u * 30u) << "trial " << trial;
    for (const auto& [p, k] : hits) {
      ASSERT_EQ(k, 1) << "pixel " << p.first << "," << p.second << " trial " << trial;
      ASSERT_TRUE(p.first >= 0 && p.first < 40 && p.second >= 0 && p.second < 30);
    }
  }
}

}  // namespace
}  // namespace rastsim
