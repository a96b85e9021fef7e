// SPDX-License-Identifier: Apache-2.0
#include "ref/circle_raster.h"

#include <algorithm>
#include <map>

namespace rastsim {

std::vector<std::pair<int64_t, int64_t>> midpoint_circle_octant(int64_t r) {
  std::vector<std::pair<int64_t, int64_t>> pts;
  int64_t x = 0, y = r;
  int64_t d4 = 5 - 4 * r;  // 4 F(1, r - 1/2)
  pts.emplace_back(x, y);
  while (x < y) {
    if (d4 >= 0) {  // SE
      d4 += 4 * (2 * (x - y) + 5);
      --y;
    } else {        // E
      d4 += 4 * (2 * x + 3);
    }
    ++x;
    pts.emplace_back(x, y);
  }
  return pts;
}

std::vector<std::pair<int, int>> circle_outline(int cx, int cy, int r) {
  std::vector<std::pair<int, int>> px;  // (y, x) for row-major sorting
  for (const auto& [x, y] : midpoint_circle_octant(r)) {
    const int a = int(x), b = int(y);
    for (int sx : {-1, 1})
      for (int sy : {-1, 1}) {
        px.emplace_back(cy + sy * b, cx + sx * a);
        px.emplace_back(cy + sy * a, cx + sx * b);
      }
  }
  std::sort(px.begin(), px.end());
  px.erase(std::unique(px.begin(), px.end()), px.end());
  for (auto& p : px) std::swap(p.first, p.second);
  return px;
}

std::vector<PixelSpan> circle_fill(int cx, int cy, int r) {
  std::map<int, std::pair<int, int>> rows;  // y -> [min x, max x]
  for (const auto& [x, y] : circle_outline(cx, cy, r)) {
    auto [it, fresh] = rows.try_emplace(y, x, x);
    if (!fresh) {
      it->second.first = std::min(it->second.first, x);
      it->second.second = std::max(it->second.second, x);
    }
  }
  std::vector<PixelSpan> spans;
  for (const auto& [y, lr] : rows) spans.push_back({y, lr.first, lr.second + 1});
  return spans;
}

}  // namespace rastsim
