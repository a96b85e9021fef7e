// SPDX-License-Identifier: Apache-2.0
// Scene generators for the llvmpipe comparison (see mesa_scenes.h).
#include "mesa_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>

namespace rastsim::mesa {
namespace {

constexpr int64_t kOne = int64_t{1} << kSubpixelBits;  // raw units per pixel (256)

// Uniform integer in [lo, hi] from a 64-bit engine. Written out (not
// std::uniform_int_distribution, whose output differs between standard libraries) so a
// seed names the same scene everywhere.
struct Rng {
  std::mt19937_64 eng;
  explicit Rng(uint64_t seed) : eng(seed) {}
  int64_t range(int64_t lo, int64_t hi) { return lo + int64_t(eng() % uint64_t(hi - lo + 1)); }
  bool chance(int percent) { return range(0, 99) < percent; }
};

// Where a coordinate may fall inside its pixel.
enum class Grid { Centre, Corner, Half, Any, Mixed };

// Puts a raw coordinate on the chosen grid (rounding down to it).
int64_t on_grid(Rng& rng, int64_t raw, Grid g) {
  if (g == Grid::Mixed) g = static_cast<Grid>(rng.range(0, 3));
  const int64_t px = raw >= 0 ? raw / kOne : -((-raw + kOne - 1) / kOne);  // floor
  switch (g) {
    case Grid::Centre: return px * kOne + kOne / 2;
    case Grid::Corner: return px * kOne;
    case Grid::Half: return (raw >= 0 ? raw / (kOne / 2) : -((-raw + kOne / 2 - 1) / (kOne / 2))) * (kOne / 2);
    default: return raw;
  }
}

Grid scene_grid(Rng& rng) { return static_cast<Grid>(rng.range(0, 4)); }

GridTri tri(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2) {
  return GridTri{{x0, x1, x2}, {y0, y1, y2}};
}

std::vector<GridTri> tiny(Rng& rng, int n, int w, int h) {
  std::vector<GridTri> out;
  const Grid g = scene_grid(rng);
  for (int i = 0; i < n; ++i) {
    const int64_t cx = rng.range(4 * kOne, (w - 4) * kOne), cy = rng.range(4 * kOne, (h - 4) * kOne);
    const int64_t ext = rng.range(1, 3 * kOne);  // up to 3 px
    GridTri t;
    for (int v = 0; v < 3; ++v) {
      t.x[v] = on_grid(rng, cx + rng.range(-ext, ext), g);
      t.y[v] = on_grid(rng, cy + rng.range(-ext, ext), g);
    }
    out.push_back(t);
  }
  return out;
}

std::vector<GridTri> sliver(Rng& rng, int n, int w, int h) {
  std::vector<GridTri> out;
  const Grid g = scene_grid(rng);
  for (int i = 0; i < n; ++i) {
    const int64_t len = rng.range(16, 600) * kOne;
    const int64_t x0 = on_grid(rng, rng.range(0, w * kOne), g), y0 = on_grid(rng, rng.range(0, h * kOne), g);
    // Direction: axis-aligned, diagonal or any, so slivers lie along pixel-centre rows too.
    int64_t dx, dy;
    switch (rng.range(0, 3)) {
      case 0: dx = len, dy = 0; break;
      case 1: dx = 0, dy = len; break;
      case 2: dx = len, dy = rng.chance(50) ? len : -len; break;
      default: dx = rng.range(-len, len), dy = rng.range(-len, len); break;
    }
    const int64_t x1 = on_grid(rng, x0 + dx, g), y1 = on_grid(rng, y0 + dy, g);
    // Third vertex near a point along the edge, off it by 0..4 raw units (0: collinear,
    // which both must drop).
    const int64_t num = rng.range(0, 64);
    const int64_t px = x0 + (x1 - x0) * num / 64, py = y0 + (y1 - y0) * num / 64;
    const int64_t off = rng.range(0, 4);
    out.push_back(tri(x0, y0, x1, y1, px + (rng.chance(50) ? off : -off), py + (rng.chance(50) ? off : -off)));
  }
  return out;
}

std::vector<GridTri> large(Rng& rng, int n, int w, int h) {
  std::vector<GridTri> out;
  const Grid g = scene_grid(rng);
  // Up to 64, 256 or 3000 px beyond each framebuffer side (llvmpipe's viewport reaches
  // 4096 px, so nothing is clipped; large bounding boxes take its 64-bit setup path).
  const int64_t margins[] = {64, 256, 3000};
  const int64_t m = margins[rng.range(0, 2)] * kOne;
  for (int i = 0; i < n; ++i) {
    GridTri t;
    for (int v = 0; v < 3; ++v) {
      t.x[v] = on_grid(rng, rng.range(-m, w * kOne + m), g);
      t.y[v] = on_grid(rng, rng.range(-m, h * kOne + m), g);
    }
    out.push_back(t);
  }
  return out;
}

// Jittered grid meshes over random rectangles until n triangles are made.
std::vector<GridTri> mesh(Rng& rng, int n, int w, int h) {
  std::vector<GridTri> out;
  while (int(out.size()) < n) {
    const Grid g = scene_grid(rng);
    const int cols = int(rng.range(2, 8)), rows = int(rng.range(2, 8));
    const int64_t cell = rng.range(2, 40) * kOne;  // px per cell, before jitter
    const int64_t x0 = rng.range(-16 * kOne, w * kOne - cols * cell / 2);
    const int64_t y0 = rng.range(-16 * kOne, h * kOne - rows * cell / 2);
    const int64_t jit = cell / 3;  // jitter below half a cell keeps every quad convex
    std::vector<int64_t> vx((cols + 1) * (rows + 1)), vy(vx.size());
    for (int r = 0; r <= rows; ++r)
      for (int c = 0; c <= cols; ++c) {
        const size_t k = size_t(r) * (cols + 1) + c;
        vx[k] = on_grid(rng, x0 + c * cell + rng.range(-jit, jit), g);
        vy[k] = on_grid(rng, y0 + r * cell + rng.range(-jit, jit), g);
      }
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const size_t a = size_t(r) * (cols + 1) + c, b = a + 1, d = a + cols + 1, e = d + 1;
        // Random diagonal, random winding per triangle (both rasterizers take either).
        std::pair<GridTri, GridTri> q = rng.chance(50)
            ? std::pair{tri(vx[a], vy[a], vx[b], vy[b], vx[e], vy[e]), tri(vx[a], vy[a], vx[e], vy[e], vx[d], vy[d])}
            : std::pair{tri(vx[a], vy[a], vx[b], vy[b], vx[d], vy[d]), tri(vx[b], vy[b], vx[e], vy[e], vx[d], vy[d])};
        for (GridTri* t : {&q.first, &q.second}) {
          if (rng.chance(50)) std::swap(t->x[1], t->x[2]), std::swap(t->y[1], t->y[2]);
          out.push_back(*t);
        }
      }
  }
  return out;
}

// Fans: a centre and a ring of points sorted by angle; spokes on the axes and diagonals
// are frequent because ring points are chosen on an integer direction lattice.
std::vector<GridTri> fan(Rng& rng, int n, int w, int h) {
  std::vector<GridTri> out;
  while (int(out.size()) < n) {
    const Grid g = scene_grid(rng);
    const int64_t cx = on_grid(rng, rng.range(0, w * kOne), g), cy = on_grid(rng, rng.range(0, h * kOne), g);
    const int64_t radius = rng.range(2, 120) * kOne;
    const int spokes = int(rng.range(3, 24));
    std::vector<std::pair<double, std::pair<int64_t, int64_t>>> ring;
    for (int s = 0; s < spokes; ++s) {
      // Direction from a small lattice (|dx|, |dy| <= 3): many axis and 45-degree spokes.
      int64_t dx = rng.range(-3, 3), dy = rng.range(-3, 3);
      if (dx == 0 && dy == 0) dx = 1;
      const int64_t steps = std::max<int64_t>(1, radius / (std::max(std::abs(dx), std::abs(dy)) * kOne));
      const int64_t x = on_grid(rng, cx + dx * steps * kOne, g), y = on_grid(rng, cy + dy * steps * kOne, g);
      if (x == cx && y == cy) continue;
      ring.push_back({std::atan2(double(y - cy), double(x - cx)), {x, y}});
    }
    std::sort(ring.begin(), ring.end());
    const bool closed = rng.chance(50);
    for (size_t s = 0; s + 1 < ring.size() + (closed ? 1 : 0); ++s) {
      const auto& p = ring[s].second;
      const auto& q = ring[(s + 1) % ring.size()].second;
      out.push_back(tri(cx, cy, p.first, p.second, q.first, q.second));
    }
  }
  return out;
}

std::string px(int64_t raw, int frac_bits) {
  // raw / 2^F is exact in a double (|raw| < 2^53); 17 significant digits print it exactly.
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.17g", std::ldexp(double(raw), -frac_bits));
  return buf;
}

// splitmix64: a stateless hash, so equal coordinates get equal offsets.
uint64_t mix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace

const char* to_string(SceneKind k) {
  switch (k) {
    case SceneKind::Tiny: return "Tiny";
    case SceneKind::Sliver: return "Sliver";
    case SceneKind::Large: return "Large";
    case SceneKind::Mesh: return "Mesh";
    case SceneKind::Fan: return "Fan";
  }
  return "?";
}

std::vector<GridTri> make_scene(SceneKind kind, uint64_t seed, int approx_tris, int width, int height) {
  Rng rng(seed);
  switch (kind) {
    case SceneKind::Tiny: return tiny(rng, approx_tris, width, height);
    case SceneKind::Sliver: return sliver(rng, approx_tris, width, height);
    case SceneKind::Large: return large(rng, approx_tris, width, height);
    case SceneKind::Mesh: return mesh(rng, approx_tris, width, height);
    case SceneKind::Fan: return fan(rng, approx_tris, width, height);
  }
  return {};
}

std::string describe(const GridTri& t) {
  std::string s;
  for (int v = 0; v < 3; ++v)
    s += (v ? " (" : "(") + px(t.x[v], t.frac_bits) + ", " + px(t.y[v], t.frac_bits) + ")";
  return s;
}

std::vector<GridTri> off_grid(const std::vector<GridTri>& tris, int extra_bits, uint64_t seed) {
  const int64_t half = int64_t{1} << (extra_bits - 1);  // half an 8-bit LSB in new units
  const auto move = [&](int64_t c, uint64_t axis) {
    const uint64_t r = mix(seed ^ mix(uint64_t(c) * 2 + axis));
    return (c << extra_bits) + int64_t(r % uint64_t(2 * half + 1)) - half;  // offset in [-half, half]
  };
  std::vector<GridTri> out;
  for (const GridTri& t : tris) {
    GridTri o;
    o.frac_bits = t.frac_bits + extra_bits;
    for (int v = 0; v < 3; ++v) o.x[v] = move(t.x[v], 0), o.y[v] = move(t.y[v], 1);
    out.push_back(o);
  }
  return out;
}

std::vector<GridTri> snap_to_grid(const std::vector<GridTri>& tris, bool ties_to_even) {
  std::vector<GridTri> out;
  for (const GridTri& t : tris) {
    const int sh = t.frac_bits - kSubpixelBits;
    const auto round = [&](int64_t c) {
      if (sh == 0) return c;
      const int64_t fl = c >> sh, rem = c - (fl << sh), half = int64_t{1} << (sh - 1);  // floor, remainder >= 0
      if (rem > half || (rem == half && (!ties_to_even || (fl & 1)))) return fl + 1;
      return fl;
    };
    GridTri o;
    for (int v = 0; v < 3; ++v) o.x[v] = round(t.x[v]), o.y[v] = round(t.y[v]);
    out.push_back(o);
  }
  return out;
}

}  // namespace rastsim::mesa
