// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/polygon_fill.h"

#include <algorithm>

#include "ref/fixed_point.h"

namespace rastsim {

namespace {

// ceil(a / b) for b > 0.
int64_t ceil_div_i128(i128 a, i128 b) { return int64_t(a >= 0 ? (a + b - 1) / b : -((-a) / b)); }

struct Edge {
  int64_t xt, yt, xb, yb;  // top (smaller y) and bottom end
  int dir;                 // +1 drawn downwards, -1 upwards
  int64_t row_first, row_end;  // scanlines [row_first, row_end)
};

}  // namespace

const char* to_string(PolygonRule r) { return r == PolygonRule::EvenOdd ? "even_odd" : "nonzero"; }

std::vector<PixelSpan> fill_polygon(const std::vector<std::pair<int64_t, int64_t>>& v, int frac_bits,
                                    PolygonRule rule) {
  const int64_t one = int64_t{1} << frac_bits, half = one / 2;
  // Edge table, sorted by first scanline. Scanline py has y = py * one + half: it is in
  // [yt, yb) for py in [ceil((yt - half) / one), ceil((yb - half) / one)).
  std::vector<Edge> et;
  for (size_t i = 0; i < v.size(); ++i) {
    const auto [x0, y0] = v[i];
    const auto [x1, y1] = v[(i + 1) % v.size()];
    if (y0 == y1) continue;  // horizontal: no scanline crossing
    Edge e = (y0 < y1) ? Edge{x0, y0, x1, y1, +1, 0, 0} : Edge{x1, y1, x0, y0, -1, 0, 0};
    e.row_first = ceil_div_i128(e.yt - half, one);
    e.row_end = ceil_div_i128(e.yb - half, one);
    if (e.row_first < e.row_end) et.push_back(e);
  }
  std::sort(et.begin(), et.end(), [](const Edge& a, const Edge& b) { return a.row_first < b.row_first; });

  std::vector<PixelSpan> spans;
  std::vector<const Edge*> active;
  std::vector<std::pair<int64_t, int>> cross;  // (first pixel at or right of it, dir)
  size_t next = 0;
  for (int64_t py = et.empty() ? 0 : et.front().row_first; next < et.size() || !active.empty(); ++py) {
    if (active.empty() && next < et.size()) py = std::max(py, et[next].row_first);
    while (next < et.size() && et[next].row_first == py) active.push_back(&et[next++]);
    std::erase_if(active, [py](const Edge* e) { return e->row_end <= py; });
    if (active.empty()) continue;
    // Intersection x = xt + (yc - yt) (xb - xt) / (yb - yt); first centre px + 1/2 >= it:
    // px = ceil((x - half) / one) = ceil(((xt - half)(yb - yt) + (yc - yt)(xb - xt)) / (one (yb - yt))).
    const int64_t yc = py * one + half;
    cross.clear();
    for (const Edge* e : active) {
      const i128 dy = e->yb - e->yt;
      const i128 num = i128(e->xt - half) * dy + i128(yc - e->yt) * (e->xb - e->xt);
      cross.emplace_back(ceil_div_i128(num, i128(one) * dy), e->dir);
    }
    std::sort(cross.begin(), cross.end());
    int winding = 0;
    for (size_t k = 0; k < cross.size(); ++k) {
      const bool was_in = (rule == PolygonRule::EvenOdd) ? (k % 2 == 1) : (winding != 0);
      winding += cross[k].second;
      const bool now_in = (rule == PolygonRule::EvenOdd) ? (k % 2 == 0) : (winding != 0);
      if (!was_in && now_in) spans.push_back({int(py), int(cross[k].first), 0});
      if (was_in && !now_in) {
        spans.back().x1 = int(cross[k].first);
        if (spans.back().x1 <= spans.back().x0) spans.pop_back();
      }
    }
  }
  return spans;
}

}  // namespace rastsim
