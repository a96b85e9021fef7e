// SPDX-License-Identifier: Apache-2.0
// Stability of the scanline traversal (ctest label "stability"): where its arithmetic
// first fails, found by search and checked against docs/stability.md.
//
// The search: fixed shapes on the 2^-8 px grid (raster.coord_format s15.8, a 16384 x 512
// framebuffer so that screen x reaches 2^14; the shapes are about 100 x 290 px, so that
// each edge crosses many rows), translated right by a whole pixel offset M. A translation
// by whole pixels shifts the exact coverage by M and changes nothing else, so a
// difference the method shows at offset M comes from the magnitude of the coordinates
// its arithmetic holds. Offsets searched: first the geometric grid M = 0 and
// floor(2^(k/16)), k = 0, 1, ... (up to 16383 - 128); then every integer between the last
// grid point that passed and the first that failed. The figure is the smallest failing
// offset so found (failure need not be monotonic in M; the grid fixes what "first" means).
// - first wrong pixel: the smallest M at which the method's pixel set of the triangle
//   differs from a brute-force scan of the edge functions (pixel_covered);
// - first crack: a quad split along its diagonal into two triangles whose outer edges
//   are axis-aligned on pixel corners (exact in every arithmetic); the smallest M at
//   which a pixel of the exact union is in neither triangle's method set. Its first
//   overlap (a pixel in both method sets) is recorded too.
// "none" means no failure up to the largest offset. The expected figures are the rows
// of docs/stability.md, section "Scanline traversal", read by this test; running it
// prints the measured rows in the same form (the command that regenerates them).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "config/raster_state_config.h"
#include "ref/traverse.h"

namespace rastsim {
namespace {

using PixelSet = std::set<std::pair<int, int>>;
constexpr int kF = 8;
constexpr int kWidth = 16384;

RasterState state(const char* arith) {
  Config cfg;
  for (std::string s : {"display.width=16384", "display.height=512", "raster.coord_format=s15.8",
                        "raster.traversal=scanline"})
    cfg.apply_override(s);
  cfg.apply_override(std::string("raster.scanline_arith=") + arith);
  return raster_state_from_config(cfg);
}

// A triangle of absolute pixel coordinates in 1/256 px (exact on the s15.8 grid).
struct Tri256 { int x[3], y[3]; };

SetupTriangle setup(const Tri256& s, int dx, const RasterState& st) {
  std::array<SceneVertex, 3> v;
  for (int i = 0; i < 3; ++i) {
    v[i].x = Q64{i128(s.x[i] + dx * 256) << (Q64::kFracBits - kF)};
    v[i].y = Q64{i128(s.y[i]) << (Q64::kFracBits - kF)};
  }
  SetupTriangle t;
  EXPECT_EQ(setup_triangle(v, st, SourceLoc{}, t), SetupOutcome::Accepted);
  return t;
}

PixelSet exact_set(const SetupTriangle& t) {
  PixelSet s;
  for (int y = t.bbox.y0; y < t.bbox.y1; ++y)
    for (int x = t.bbox.x0; x < t.bbox.x1; ++x)
      if (pixel_covered(t, x, y, kF)) s.insert({x, y});
  return s;
}

PixelSet method_set(const SetupTriangle& t, const RasterState& st) {
  PixelSet s;
  TraversalCounters c;
  traverse(t, traversal_params(st), c, [&](int x, int y) { s.insert({x, y}); });
  return s;
}

// The shapes: a generic triangle, (0.30, 0.20) (97.11, 30.43) (21.70, 287.93) px, and a
// quad from (0, 2) to (64, 290) split along the diagonal (0, 2)-(64, 290) (slope 4.5: not
// a power of two, so the gradient is rounded).
const Tri256 kTri{{77, 24860, 5555}, {51, 7790, 73710}};
const Tri256 kQuadUpper{{0, 64 * 256, 64 * 256}, {2 * 256, 2 * 256, 290 * 256}};
const Tri256 kQuadLower{{0, 64 * 256, 0}, {2 * 256, 290 * 256, 290 * 256}};
constexpr int kMaxOffset = kWidth - 128;

std::vector<int> grid() {
  std::vector<int> g{0};
  for (int k = 0;; ++k) {
    const int m = int(std::floor(std::pow(2.0, k / 16.0)));
    if (m > kMaxOffset) break;
    if (m != g.back()) g.push_back(m);
  }
  return g;
}

struct Figures {
  std::optional<int> first_wrong, first_crack, first_overlap;
};

std::string fig(const std::optional<int>& v) { return v ? std::to_string(*v) : "none"; }

// The three failure tests at one offset.
bool wrong_at(int m, const RasterState& st) {
  const SetupTriangle t = setup(kTri, m, st);
  return method_set(t, st) != exact_set(t);
}
bool crack_at(int m, const RasterState& st) {
  const SetupTriangle u = setup(kQuadUpper, m, st), l = setup(kQuadLower, m, st);
  const PixelSet mu = method_set(u, st), ml = method_set(l, st);
  for (const SetupTriangle* t : {&u, &l})
    for (const auto& p : exact_set(*t))
      if (!mu.count(p) && !ml.count(p)) return true;
  return false;
}
bool overlap_at(int m, const RasterState& st) {
  const SetupTriangle u = setup(kQuadUpper, m, st), l = setup(kQuadLower, m, st);
  const PixelSet mu = method_set(u, st), ml = method_set(l, st);
  for (const auto& p : mu)
    if (ml.count(p)) return true;
  return false;
}

std::optional<int> first_failure(bool (*fails)(int, const RasterState&), const RasterState& st) {
  const std::vector<int> g = grid();
  for (size_t i = 0; i < g.size(); ++i) {
    if (!fails(g[i], st)) continue;
    for (int m = i ? g[i - 1] + 1 : 0; m < g[i]; ++m)
      if (fails(m, st)) return m;
    return g[i];
  }
  return std::nullopt;
}

Figures search(const char* arith) {
  const RasterState st = state(arith);
  return {first_failure(wrong_at, st), first_failure(crack_at, st), first_failure(overlap_at, st)};
}

// The rows of docs/stability.md's "Scanline traversal" section:
// | `scanline.<arith>.<figure>` | description | value |
std::map<std::string, std::string> documented_rows() {
  std::ifstream in(std::string(RASTSIM_SOURCE_DIR) + "/docs/stability.md");
  EXPECT_TRUE(in) << "docs/stability.md missing";
  std::map<std::string, std::string> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| `scanline.", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '|');) {
      const auto b = c.find_first_not_of(" `"), e = c.find_last_not_of(" `");
      cells.push_back(b == std::string::npos ? "" : c.substr(b, e - b + 1));
    }
    if (cells.size() >= 4) rows[cells[1]] = cells[3];
  }
  return rows;
}

class ScanlineStability : public ::testing::TestWithParam<const char*> {};

TEST_P(ScanlineStability, FailurePointsMatchDocs) {
  const char* arith = GetParam();
  const Figures f = search(arith);
  const std::string p = std::string("scanline.") + arith + ".";
  std::cout << "| `" << p << "first_wrong_offset_px` | first pixel wrong, triangle | " << fig(f.first_wrong) << " |\n"
            << "| `" << p << "first_crack_offset_px` | first crack, shared diagonal | " << fig(f.first_crack) << " |\n"
            << "| `" << p << "first_overlap_offset_px` | first overlap, shared diagonal | " << fig(f.first_overlap)
            << " |\n";
  const auto rows = documented_rows();
  auto expect_row = [&](const std::string& key, const std::optional<int>& v) {
    const auto it = rows.find(key);
    ASSERT_NE(it, rows.end()) << key << " has no row in docs/stability.md";
    EXPECT_EQ(it->second, fig(v)) << key << " moved: update docs/stability.md and say why";
  };
  expect_row(p + "first_wrong_offset_px", f.first_wrong);
  expect_row(p + "first_crack_offset_px", f.first_crack);
  expect_row(p + "first_overlap_offset_px", f.first_overlap);
}

INSTANTIATE_TEST_SUITE_P(Arith, ScanlineStability, ::testing::Values("f32", "f64", "fixed"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace rastsim
