// SPDX-License-Identifier: Apache-2.0
// Watertightness through the whole reference pipeline (render_scene).
//
// Seeded random triangulations that tile the viewport exactly (or a larger region in
// the guard band, clipped) are rendered and every fragment is counted through the
// FragmentSink: each viewport pixel must be hit exactly once, none outside it, so the
// total is width * height; and with raster.samples = 2, 4, 8, 16 each SAMPLE of each
// viewport pixel exactly once (the top-left rule per sample). Mesh kinds:
// - jittered grids: border vertices on the viewport border, interior vertices jittered
//   (some exactly on pixel centres or corners), each quad split along a random
//   diagonal, each triangle given a random winding;
// - fans around an interior point over the viewport rectangle with extra border
//   vertices (some at pixel-centre x or y), and over a convex polygon on a circle that
//   encloses the viewport (vertices in the guard band).
// Vertices are placed on the format's LSB grid (plus, for some, an offset below half an
// LSB that snapping removes) and given as Q64::from_int, exact decimal literals
// (Q64::parse_decimal) or raw Q64 values. The snapped mesh is checked to be a proper
// triangulation (every triangle keeps its orientation) before rendering, so the
// expectation "once per pixel" follows from geometry, not from the model.
//
// A negative control shows the check can fail: with fill_rule inclusive (exclusive) a
// diagonal through pixel centres is hit twice (not at all).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/sample_pattern.h"

namespace rastsim {
namespace {

struct WtCase {
  const char* name;
  FixedFormat fmt;
  int vw, vh;
  int tile;
  int meshes;  // per mesh kind
  uint64_t seed;
};
void PrintTo(const WtCase& c, std::ostream* os) { *os << c.name; }

// A vertex on the LSB grid: a, b are absolute raw coordinates (units 2^-F px from the
// framebuffer's top-left corner).
struct GridPt { int64_t a, b; };

i128 orient(const GridPt& p, const GridPt& q, const GridPt& r) {
  return i128(q.a - p.a) * (r.b - p.b) - i128(q.b - p.b) * (r.a - p.a);
}

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Exact decimal literal for raw / 2^F (F <= 30): integer part and F fraction digits.
std::string decimal_of(int64_t raw, int f) {
  const bool neg = raw < 0;
  const uint64_t m = uint64_t(neg ? -raw : raw);
  uint64_t frac = m & ((uint64_t{1} << f) - 1);
  for (int i = 0; i < f; ++i) frac *= 5;  // frac / 2^F = frac * 5^F / 10^F
  std::string fd = std::to_string(frac);
  fd = std::string(size_t(f) - fd.size(), '0') + fd;
  return (neg ? "-" : "") + std::to_string(m >> f) + "." + fd;
}

// Guard band: the format reaches absolute pixel positions [o - 2^I, o + 2^I) around
// the origin o = floor(n / 2); keep a pixel clear of both ends. Returns the pixels a
// mesh may extend beyond each viewport side, {x, y}.
std::pair<int64_t, int64_t> guard_band(const WtCase& c) {
  const int64_t ox = c.vw / 2, oy = c.vh / 2, reach = int64_t{1} << c.fmt.int_bits;
  return {std::max<int64_t>(0, std::min(reach - ox, reach - (c.vw - ox)) - 1),
          std::max<int64_t>(0, std::min(reach - oy, reach - (c.vh - oy)) - 1)};
}

// A circle enclosing the viewport (radius 1.25 half-diagonals) fits in the guard band.
bool enclosing_circle_fits(const WtCase& c) {
  const auto [gx, gy] = guard_band(c);
  const double half_diag = 0.5 * std::hypot(double(c.vw), double(c.vh));
  const double room = std::min({double(gx) + 0.5 * c.vw, double(gy) + 0.5 * c.vh}) - 1.0;
  return room >= half_diag * 1.25;
}

class Watertight : public ::testing::TestWithParam<WtCase> {
 protected:
  void SetUp() override {
    const WtCase& c = GetParam();
    F = c.fmt.frac_bits;
    one = int64_t{1} << F;
    std::tie(guard_x, guard_y) = guard_band(c);
  }

  int64_t uni(std::mt19937_64& rng, int64_t lo, int64_t hi) {
    return lo + int64_t(rng() % uint64_t(hi - lo + 1));
  }

  // The scene vertex for a grid point, in one of three spellings.
  SceneVertex vertex(std::mt19937_64& rng, const GridPt& p) {
    SceneVertex v;
    auto coord = [&](int64_t raw) {
      const int how = int(rng() % 3);
      if (how == 0 && raw % one == 0) return Q64::from_int(raw / one);
      if (how == 1) return Q64::parse_decimal(decimal_of(raw, F));
      const int sh = 64 - F;
      const i128 lim = (i128(1) << (sh - 1)) - 1;  // strictly below half an LSB
      const i128 off = i128(rng() % uint64_t(lim)) * ((rng() % 2) ? 1 : -1);
      return Q64{(i128(raw) << sh) + off};
    };
    v.x = coord(p.a);
    v.y = coord(p.b);
    v.z = double(rng() % 1000) / 1000.0;
    v.r = uint8_t(rng());
    v.g = uint8_t(rng());
    v.b = uint8_t(rng());
    return v;
  }

  // Renders `tris` (grid points, orientation already checked) as a triangle list with
  // random windings and asserts every viewport pixel is hit exactly once.
  void render_and_check(std::mt19937_64& rng, const std::vector<std::array<GridPt, 3>>& tris,
                        const std::string& what) {
    const WtCase& c = GetParam();
    SCOPED_TRACE(what + ", " + std::to_string(tris.size()) + " triangles");
    CmdPrimitives prims;
    for (auto t : tris) {
      if (rng() % 2) std::swap(t[1], t[2]);  // either winding
      for (const GridPt& p : t) prims.vertices.push_back(vertex(rng, p));
    }
    Scene scene;
    scene.source = "watertight";
    scene.commands.push_back({CmdViewport{c.vw, c.vh}, {"gen", 1}});
    scene.commands.push_back({CmdClear{0, 0, 0}, {"gen", 2}});
    scene.commands.push_back({std::move(prims), {"gen", 3}});
    // Every sample count: each sample of each viewport pixel is hit exactly once (the
    // mask bits of the fragments) when its position lies in the mesh's half-open
    // bounding rectangle (top-left rule on its left and top sides), never otherwise:
    // W x H x S samples in all when F >= 4, where every offset is inside [-8, 7]/16 px;
    // on a coarser grid an offset can snap to +1/2 px, onto the pixel's right or bottom
    // edge, which on the last column or row is the mesh's excluded boundary.
    int64_t mx0 = INT64_MAX, my0 = INT64_MAX, mx1 = INT64_MIN, my1 = INT64_MIN;
    for (const auto& t : tris)
      for (const GridPt& p : t) {
        mx0 = std::min(mx0, p.a), mx1 = std::max(mx1, p.a);
        my0 = std::min(my0, p.b), my1 = std::max(my1, p.b);
      }
    for (int S : {1, 2, 4, 8, 16}) {
      SCOPED_TRACE("raster.samples = " + std::to_string(S));
      RasterState st = raster_state_from_config(Config{});
      st.coord_format = c.fmt;
      st.tile_size = c.tile;
      st.fill_rule = FillRule::TopLeft;
      st.samples = S;
      st.fb_width = c.vw + 3;  // a framebuffer margin the viewport must keep clear
      st.fb_height = c.vh + 2;
      RenderStats stats;
      std::vector<uint32_t> hits(size_t(st.fb_width) * st.fb_height * S, 0);
      uint64_t outside = 0;
      render_scene(scene, st, stats, [&](const Fragment& f) {
        if (f.x < 0 || f.y < 0 || f.x >= c.vw || f.y >= c.vh) ++outside;
        else
          for (int s = 0; s < S; ++s)
            if ((f.mask >> s) & 1) ++hits[(size_t(f.y) * st.fb_width + f.x) * S + s];
      });
      EXPECT_EQ(outside, 0u);
      const SamplePattern& pat = sample_pattern(S, F);
      auto inside = [&](int x, int y, int s) {
        const int64_t sx = int64_t(x) * one + one / 2 + pat.dx[size_t(s)];
        const int64_t sy = int64_t(y) * one + one / 2 + pat.dy[size_t(s)];
        return sx >= mx0 && sx < mx1 && sy >= my0 && sy < my1;
      };
      uint64_t expected = 0;
      for (int y = 0; y < c.vh; ++y)
        for (int x = 0; x < c.vw; ++x)
          for (int s = 0; s < S; ++s) expected += inside(x, y, s);
      if (F >= 4) {
        EXPECT_EQ(expected, uint64_t(c.vw) * c.vh * S);
      }
      EXPECT_EQ(stats.traversal.samples_covered, expected);
      if (S == 1) {
        EXPECT_EQ(stats.traversal.fragments, uint64_t(c.vw) * c.vh);
      }
      EXPECT_EQ(stats.triangles_in, tris.size());
      int reported = 0;
      for (int y = 0; y < c.vh; ++y)
        for (int x = 0; x < c.vw; ++x)
          for (int s = 0; s < S; ++s) {
            const uint32_t h = hits[(size_t(y) * st.fb_width + x) * S + s];
            if (h != (inside(x, y, s) ? 1u : 0u) && reported++ < 5)
              ADD_FAILURE() << "pixel (" << x << ", " << y << ") sample " << s << " hit " << h << " times";
          }
    }
  }

  int F = 0;
  int64_t one = 0;
  int64_t guard_x = 0, guard_y = 0;  // px the mesh may extend beyond each viewport side
};

// Jittered grid over [x0, x1] x [y0, y1] (pixels); returns false when a triangle came out
// inverted or flat after snapping (the caller retries).
bool grid_mesh(std::mt19937_64& rng, int64_t one, int64_t x0, int64_t y0, int64_t x1, int64_t y1, int nx,
               int ny, std::vector<std::array<GridPt, 3>>& out) {
  auto uni = [&](int64_t lo, int64_t hi) { return lo + int64_t(rng() % uint64_t(hi - lo + 1)); };
  std::vector<GridPt> g(size_t(nx + 1) * (ny + 1));
  const int64_t w = (x1 - x0) * one, h = (y1 - y0) * one;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      GridPt p{x0 * one + w * i / nx, y0 * one + h * j / ny};
      // Interior coordinates move by up to an eighth of a cell, then maybe half a pixel
      // more onto a pixel centre or corner; border coordinates stay on the border.
      auto jitter = [&](int64_t& v, int64_t cell) {
        v += uni(-cell / 8, cell / 8);
        const int r = int(rng() % 8);
        if (r == 0) v = floor_div(v, one) * one + one / 2;     // centre of its pixel
        if (r == 1) v = floor_div(v + one / 2, one) * one;     // nearest corner
      };
      if (i > 0 && i < nx) jitter(p.a, w / nx);
      if (j > 0 && j < ny) jitter(p.b, h / ny);
      g[size_t(j) * (nx + 1) + i] = p;
    }
  }
  out.clear();
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const GridPt& p00 = g[size_t(j) * (nx + 1) + i];
      const GridPt& p10 = g[size_t(j) * (nx + 1) + i + 1];
      const GridPt& p01 = g[size_t(j + 1) * (nx + 1) + i];
      const GridPt& p11 = g[size_t(j + 1) * (nx + 1) + i + 1];
      // Clockwise on screen (y down): 00 -> 10 -> 11 and so on.
      if (rng() % 2) {
        out.push_back({p00, p10, p11});
        out.push_back({p00, p11, p01});
      } else {
        out.push_back({p00, p10, p01});
        out.push_back({p10, p11, p01});
      }
    }
  }
  for (const auto& t : out)
    if (orient(t[0], t[1], t[2]) <= 0) return false;
  return true;
}

TEST_P(Watertight, JitteredGridMeshes) {
  const WtCase& c = GetParam();
  SCOPED_TRACE("seed " + std::to_string(c.seed));
  std::mt19937_64 rng(c.seed);
  for (int m = 0; m < c.meshes; ++m) {
    // Half the meshes tile exactly the viewport, half a larger region in the guard band.
    const bool overscan = m % 2 == 1 && (guard_x > 0 || guard_y > 0);
    const int64_t gx = overscan ? uni(rng, 0, std::min<int64_t>(guard_x, 3 * c.vw)) : 0;
    const int64_t gy = overscan ? uni(rng, 0, std::min<int64_t>(guard_y, 3 * c.vh)) : 0;
    const int nx = int(uni(rng, 1, std::max<int64_t>(1, std::min<int64_t>(24, (c.vw + 2 * gx) / 2))));
    const int ny = int(uni(rng, 1, std::max<int64_t>(1, std::min<int64_t>(24, (c.vh + 2 * gy) / 2))));
    std::vector<std::array<GridPt, 3>> tris;
    int tries = 0;
    while (!grid_mesh(rng, one, -gx, -gy, c.vw + gx, c.vh + gy, nx, ny, tris)) ASSERT_LT(++tries, 1000);
    render_and_check(rng, tris,
                     "grid " + std::to_string(m) + " (" + std::to_string(nx) + "x" + std::to_string(ny) +
                         " cells, overscan " + std::to_string(gx) + "," + std::to_string(gy) + ")");
  }
}

TEST_P(Watertight, FansOverTheViewportRectangle) {
  const WtCase& c = GetParam();
  SCOPED_TRACE("seed " + std::to_string(c.seed));
  std::mt19937_64 rng(c.seed ^ 0xfa);
  for (int m = 0; m < c.meshes; ++m) {
    const int64_t gx = (m % 2) ? uni(rng, 0, std::min<int64_t>(guard_x, c.vw)) : 0;
    const int64_t gy = (m % 2) ? uni(rng, 0, std::min<int64_t>(guard_y, c.vh)) : 0;
    const int64_t x0 = -gx * one, y0 = -gy * one, x1 = (c.vw + gx) * one, y1 = (c.vh + gy) * one;
    // Perimeter clockwise on screen from the top-left corner; each side gets random
    // extra points, half of them at pixel-centre positions.
    auto side = [&](int64_t lo, int64_t hi) {
      std::vector<int64_t> v;
      const int n = int(rng() % 6);
      for (int k = 0; k < n; ++k) {
        int64_t p = uni(rng, lo, hi);
        if (rng() % 2) p = floor_div(p, one) * one + one / 2;
        if (p > lo && p < hi) v.push_back(p);
      }
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    };
    std::vector<GridPt> ring{{x0, y0}};
    for (int64_t a : side(x0, x1)) ring.push_back({a, y0});
    ring.push_back({x1, y0});
    for (int64_t b : side(y0, y1)) ring.push_back({x1, b});
    ring.push_back({x1, y1});
    auto bottom = side(x0, x1);
    std::reverse(bottom.begin(), bottom.end());
    for (int64_t a : bottom) ring.push_back({a, y1});
    ring.push_back({x0, y1});
    auto left = side(y0, y1);
    std::reverse(left.begin(), left.end());
    for (int64_t b : left) ring.push_back({x0, b});
    // Centre strictly inside, sometimes exactly on a pixel centre.
    GridPt ctr{uni(rng, x0 + 1, x1 - 1), uni(rng, y0 + 1, y1 - 1)};
    if (rng() % 2) {
      ctr = {floor_div(ctr.a, one) * one + one / 2, floor_div(ctr.b, one) * one + one / 2};
      ctr.a = std::clamp(ctr.a, x0 + 1, x1 - 1);
      ctr.b = std::clamp(ctr.b, y0 + 1, y1 - 1);
    }
    std::vector<std::array<GridPt, 3>> tris;
    for (size_t k = 0; k < ring.size(); ++k) tris.push_back({ctr, ring[k], ring[(k + 1) % ring.size()]});
    for (const auto& t : tris) ASSERT_GT(orient(t[0], t[1], t[2]), 0);
    render_and_check(rng, tris, "fan " + std::to_string(m));
  }
}

// The same, with the fan given as a Topology::Fan command over a convex polygon whose
// vertices lie on a circle enclosing the viewport (so every edge is clipped away).
// Instantiated only for the cases whose guard band holds the circle (enclosing_circle_fits).
class WatertightCircle : public Watertight {};
TEST_P(WatertightCircle, FansOverAnEnclosingCircle) {
  const WtCase& c = GetParam();
  const double half_diag = 0.5 * std::hypot(double(c.vw), double(c.vh));
  const double cx = 0.5 * c.vw, cy = 0.5 * c.vh;
  ASSERT_TRUE(enclosing_circle_fits(c));
  const double room = std::min({double(guard_x) + cx, double(guard_y) + cy}) - 1.0;
  SCOPED_TRACE("seed " + std::to_string(c.seed));
  std::mt19937_64 rng(c.seed ^ 0xc1);
  for (int m = 0; m < c.meshes; ++m) {
    const double radius = half_diag * 1.25 + double(rng() % 1000) / 1000.0 * (room - half_diag * 1.25);
    // Angles at least 10 degrees apart and at most 70 apart: cos(35 deg) * 1.25 > 1, so
    // the polygon contains the viewport's circumcircle.
    std::vector<double> ang;
    for (double a = 0; a < 360.0 - 10.0;) {
      ang.push_back(a);
      a += 10.0 + double(rng() % 6000) / 100.0;
    }
    if (360.0 - ang.back() > 70.0) ang.push_back(ang.back() + (360.0 - ang.back()) / 2);
    std::vector<GridPt> ring;
    for (double a : ang) {
      const double r = a * M_PI / 180.0;
      ring.push_back({int64_t(std::llround((cx + radius * std::cos(r)) * double(one))),
                      int64_t(std::llround((cy + radius * std::sin(r)) * double(one)))});
    }
    // Increasing angle with y down is clockwise on screen; check convexity exactly.
    for (size_t k = 0; k < ring.size(); ++k)
      ASSERT_GT(orient(ring[k], ring[(k + 1) % ring.size()], ring[(k + 2) % ring.size()]), 0);
    GridPt ctr{uni(rng, 0, c.vw * one), uni(rng, 0, c.vh * one)};
    if (rng() % 2) ctr = {floor_div(ctr.a, one) * one + one / 2, floor_div(ctr.b, one) * one + one / 2};
    std::vector<std::array<GridPt, 3>> tris;
    for (size_t k = 0; k < ring.size(); ++k) tris.push_back({ctr, ring[k], ring[(k + 1) % ring.size()]});
    for (const auto& t : tris) ASSERT_GT(orient(t[0], t[1], t[2]), 0);
    if (m % 2 == 0) {
      render_and_check(rng, tris, "circle fan (list) " + std::to_string(m));
      continue;
    }
    // As a Topology::Fan command: centre, ring..., ring[0].
    SCOPED_TRACE("circle fan (fan topology) " + std::to_string(m));
    CmdPrimitives prims;
    prims.topology = Topology::Fan;
    prims.vertices.push_back(vertex(rng, ctr));
    for (const GridPt& p : ring) prims.vertices.push_back(vertex(rng, p));
    prims.vertices.push_back(prims.vertices[1]);
    Scene scene;
    scene.commands.push_back({CmdViewport{c.vw, c.vh}, {"gen", 1}});
    scene.commands.push_back({std::move(prims), {"gen", 2}});
    RasterState st = raster_state_from_config(Config{});
    st.coord_format = c.fmt;
    st.tile_size = c.tile;
    st.fb_width = c.vw;
    st.fb_height = c.vh;
    RenderStats stats;
    std::vector<uint32_t> hits(size_t(c.vw) * c.vh, 0);
    render_scene(scene, st, stats, [&](const Fragment& f) { ++hits[size_t(f.y) * c.vw + f.x]; });
    EXPECT_EQ(stats.triangles_in, ring.size());
    EXPECT_EQ(stats.traversal.fragments, uint64_t(c.vw) * c.vh);
    EXPECT_EQ(std::count(hits.begin(), hits.end(), 1u), int64_t(c.vw) * c.vh);
  }
}

const std::vector<WtCase> kWtCases = {
    WtCase{"S7F16Max254Tile16", {7, 16}, 254, 254, 16, 16, 0x3a7e01},
    WtCase{"S7F16Odd127x93Tile8", {7, 16}, 127, 93, 8, 24, 0x3a7e02},
    WtCase{"S7F16Small40x30Tile4", {7, 16}, 40, 30, 4, 40, 0x3a7e03},
    WtCase{"S15F8W640H480Tile64", {15, 8}, 640, 480, 64, 8, 0x3a7e04},
    WtCase{"S10F4W200H150Tile32", {10, 4}, 200, 150, 32, 16, 0x3a7e05},
    WtCase{"S10F4W200H150Tile2", {10, 4}, 200, 150, 2, 12, 0x3a7e06},
    WtCase{"S3F4Max14Tile4", {3, 4}, 14, 14, 4, 100, 0x3a7e07},
    WtCase{"S3F4W9H5Tile128", {3, 4}, 9, 5, 128, 100, 0x3a7e08},
    WtCase{"S2F1Max6Tile2", {2, 1}, 6, 6, 2, 100, 0x3a7e09},
    WtCase{"S14F16W301H257Tile128", {14, 16}, 301, 257, 128, 12, 0x3a7e0a}};

std::string wt_name(const ::testing::TestParamInfo<WtCase>& i) { return i.param.name; }

std::vector<WtCase> circle_cases() {
  std::vector<WtCase> v;
  for (const WtCase& c : kWtCases)
    if (enclosing_circle_fits(c)) v.push_back(c);
  return v;
}

INSTANTIATE_TEST_SUITE_P(Formats, Watertight, ::testing::ValuesIn(kWtCases), wt_name);
INSTANTIATE_TEST_SUITE_P(Formats, WatertightCircle, ::testing::ValuesIn(circle_cases()), wt_name);

// Negative control on an 8x8 viewport split along the diagonal (0,0)-(8,8), which passes
// through the centres (k + 1/2, k + 1/2): top-left and bottom-right hit each pixel once;
// inclusive hits the 8 diagonal pixels twice (72 fragments), exclusive drops them (56).
TEST(WatertightControl, SharedEdgeThroughCentresDependsOnFillRule) {
  struct Case { FillRule rule; uint32_t diag_hits; uint64_t total; };
  for (const Case& k : {Case{FillRule::TopLeft, 1, 64}, Case{FillRule::BottomRight, 1, 64},
                        Case{FillRule::Inclusive, 2, 72}, Case{FillRule::Exclusive, 0, 56}}) {
    SCOPED_TRACE("fill rule " + std::to_string(int(k.rule)));
    CmdPrimitives prims;
    for (auto [x, y] : {std::pair{0, 0}, {8, 0}, {8, 8}, {0, 0}, {8, 8}, {0, 8}}) {
      SceneVertex v;
      v.x = Q64::from_int(x);
      v.y = Q64::from_int(y);
      prims.vertices.push_back(v);
    }
    Scene scene;
    scene.commands.push_back({CmdViewport{8, 8}, {"gen", 1}});
    scene.commands.push_back({std::move(prims), {"gen", 2}});
    RasterState st = raster_state_from_config(Config{});
    st.fill_rule = k.rule;
    st.tile_size = 4;
    st.fb_width = st.fb_height = 8;
    RenderStats stats;
    std::vector<uint32_t> hits(64, 0);
    render_scene(scene, st, stats, [&](const Fragment& f) { ++hits[size_t(f.y) * 8 + f.x]; });
    EXPECT_EQ(stats.traversal.fragments, k.total);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        EXPECT_EQ(hits[size_t(y) * 8 + x], x == y ? k.diag_hits : 1u) << x << "," << y;
  }
}

}  // namespace
}  // namespace rastsim
