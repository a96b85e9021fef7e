// SPDX-License-Identifier: Apache-2.0
#include "ref/coarse_raster.h"

#include <algorithm>

#include "ref/sample_pattern.h"

namespace rastsim {

namespace {
int floor_div(int a, int b) { return (a >= 0) ? a / b : -((-a + b - 1) / b); }
}  // namespace

PixelRect tile_range(const PixelRect& bbox, int tile_size) {
  if (bbox.empty()) return {};
  return {floor_div(bbox.x0, tile_size), floor_div(bbox.y0, tile_size),
          floor_div(bbox.x1 - 1, tile_size) + 1, floor_div(bbox.y1 - 1, tile_size) + 1};
}

PixelRect tile_footprint(const PixelRect& bbox, int tile_size, int tx, int ty) {
  const PixelRect tile{tx * tile_size, ty * tile_size, (tx + 1) * tile_size, (ty + 1) * tile_size};
  return tile.intersect(bbox);
}

TileClass classify_tile(const SetupTriangle& t, const PixelRect& fp, int frac_bits) {
  const SamplePattern& p = sample_pattern(t.samples, frac_bits);
  const int64_t sx_lo = t.sample_x(fp.x0, frac_bits) + p.dx_min, sx_hi = t.sample_x(fp.x1 - 1, frac_bits) + p.dx_max;
  const int64_t sy_lo = t.sample_y(fp.y0, frac_bits) + p.dy_min, sy_hi = t.sample_y(fp.y1 - 1, frac_bits) + p.dy_max;
  bool all_inside = true;
  for (const auto& e : t.edge) {
    // Corner where the edge is largest / smallest over the footprint's sample grid.
    const i128 e_max = e.eval(e.a >= 0 ? sx_hi : sx_lo, e.b >= 0 ? sy_hi : sy_lo) + e.bias;
    if (e_max < 0) return TileClass::Rejected;
    const i128 e_min = e.eval(e.a >= 0 ? sx_lo : sx_hi, e.b >= 0 ? sy_lo : sy_hi) + e.bias;
    all_inside &= e_min >= 0;
  }
  return all_inside ? TileClass::Accepted : TileClass::Partial;
}

}  // namespace rastsim
