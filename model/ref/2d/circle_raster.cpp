// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/circle_raster.h"

#include <cmath>

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

std::pair<int64_t, int64_t> arc_direction(double deg) {
  const double t = deg * (3.14159265358979323846 / 180.0);
  const double scale = 16777216.0;  // 2^24: the direction's resolution
  return {int64_t(std::llround(std::cos(t) * scale)), int64_t(std::llround(std::sin(t) * scale))};
}

bool arc_contains(std::pair<int64_t, int64_t> d0, std::pair<int64_t, int64_t> d1, double sweep_deg, int64_t x,
                  int64_t y) {
  const int64_t qx = x, qy = -y;  // y up, as the directions
  if (qx == 0 && qy == 0) return true;
  // |d| < 2^25 and |q| < 2^31: products fit in int64_t.
  auto cross = [](int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * by - ay * bx; };
  auto dot = [](int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * bx + ay * by; };
  // On the ray of d (not its opposite).
  auto on_ray = [&](std::pair<int64_t, int64_t> d) {
    return cross(d.first, d.second, qx, qy) == 0 && dot(d.first, d.second, qx, qy) > 0;
  };
  if (on_ray(d0) || on_ray(d1)) return true;
  // Strictly inside the convex sector from a to b (counter-clockwise, less than 180 deg).
  auto strictly_between = [&](std::pair<int64_t, int64_t> a, std::pair<int64_t, int64_t> b) {
    return cross(a.first, a.second, qx, qy) > 0 && cross(qx, qy, b.first, b.second) > 0;
  };
  if (sweep_deg <= 180.0) {
    if (sweep_deg == 180.0) return cross(d0.first, d0.second, qx, qy) > 0;  // the half-plane left of d0
    return strictly_between(d0, d1);
  }
  // More than half a turn: everything not strictly inside the complement sector d1 -> d0.
  return !strictly_between(d1, d0);
}

std::vector<std::pair<int, int>> arc_outline(int cx, int cy, int r, double a0_deg, double a1_deg) {
  const double sweep = a1_deg - a0_deg;
  std::vector<std::pair<int, int>> out;
  const auto d0 = arc_direction(a0_deg), d1 = arc_direction(a1_deg);
  for (const auto& [x, y] : circle_outline(cx, cy, r))
    if (sweep >= 360.0 || arc_contains(d0, d1, sweep, x - cx, y - cy)) out.emplace_back(x, y);
  return out;
}

}  // namespace rastsim
