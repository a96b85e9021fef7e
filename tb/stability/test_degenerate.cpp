// SPDX-License-Identifier: Apache-2.0
// Degenerate triangles (docs/stability.md, "Degenerate triangles"): slivers of area one
// ulp, collinear and coincident vertices, vertices exactly on tile corners, pixel corners
// and pixel centres, near-collinear triangles one LSB off a line. Each triangle is drawn
// alone through the whole reference pipeline (render_scene) and its fragments compared
// with a brute-force reference written here: every pixel centre near the triangle tested
// against the three edge functions in __int128 with the top-left rule, from the raw
// vertices (never through tri_setup). Vertices lie on the format's LSB grid, so snapping
// does not move them. Counted: pixels the model gets wrong (in one set, not the other)
// and fragments outside the framebuffer; neither may be non-zero, and a crash fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "ref/pipeline.h"
#include "stability/doc_table.h"
#include "stability/stability_state.h"

namespace rastsim {
namespace {

using RawPt = std::array<int64_t, 2>;  // raw s.I.F units relative to the snapping origin
using Tri = std::array<RawPt, 3>;

i128 cross(const RawPt& o, const RawPt& a, const RawPt& b) {
  return i128(a[0] - o[0]) * (b[1] - o[1]) - i128(a[1] - o[1]) * (b[0] - o[0]);
}

// The brute-force reference: pixels (absolute) whose centre the triangle covers.
std::set<std::pair<int, int>> brute_force(Tri t, const RasterState& st) {
  std::set<std::pair<int, int>> out;
  const i128 area = cross(t[0], t[1], t[2]);
  if (area == 0) return out;          // no interior
  if (area < 0) std::swap(t[1], t[2]);  // clockwise on screen (y down): interior to the right
  const int F = st.coord_format.frac_bits;
  const int64_t ox = st.origin_x(), oy = st.origin_y();
  // Candidate pixels: the vertices' pixel range, one pixel of margin, clipped to the viewport.
  int64_t lo[2], hi[2];
  for (int a = 0; a < 2; ++a) {
    lo[a] = std::min({t[0][a], t[1][a], t[2][a]}) >> F;
    hi[a] = (std::max({t[0][a], t[1][a], t[2][a]}) >> F) + 1;
  }
  const int64_t x0 = std::max<int64_t>(lo[0] + ox - 1, 0), x1 = std::min<int64_t>(hi[0] + ox + 1, st.viewport_width);
  const int64_t y0 = std::max<int64_t>(lo[1] + oy - 1, 0), y1 = std::min<int64_t>(hi[1] + oy + 1, st.viewport_height);
  for (int64_t py = y0; py < y1; ++py)
    for (int64_t px = x0; px < x1; ++px) {
      const RawPt s = {((px - ox) << F) + (int64_t{1} << (F - 1)), ((py - oy) << F) + (int64_t{1} << (F - 1))};
      bool in = true;
      for (int i = 0; i < 3 && in; ++i) {
        const RawPt& a = t[i];
        const RawPt& b = t[(i + 1) % 3];
        const i128 w = cross(a, b, s);
        // Top-left rule (y down): a left edge goes up (b_y < a_y); a top edge is
        // horizontal with the interior below (b_x > a_x).
        const bool top_left = b[1] < a[1] || (b[1] == a[1] && b[0] > a[0]);
        in = w > 0 || (w == 0 && top_left);
      }
      if (in) out.insert({int(px), int(py)});
    }
  return out;
}

struct Tally { uint64_t triangles = 0, covered = 0, wrong = 0, outside = 0; };

void check(const Tri& t, const RasterState& st, Tally& tally) {
  const int F = st.coord_format.frac_bits;
  CmdPrimitives prims;
  for (const RawPt& p : t) {
    SceneVertex v;
    v.x.q = i128(p[0] + (st.origin_x() << F)) << (Q64::kFracBits - F);
    v.y.q = i128(p[1] + (st.origin_y() << F)) << (Q64::kFracBits - F);
    v.z = 0.5;
    prims.vertices.push_back(v);
  }
  Scene scene{"degenerate", {Command{prims, SourceLoc{"degenerate", 1}}}};
  std::set<std::pair<int, int>> model;
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) {
    if (f.x < 0 || f.y < 0 || f.x >= st.fb_width || f.y >= st.fb_height) ++tally.outside;
    if (!model.insert({f.x, f.y}).second) ++tally.wrong;  // a pixel twice from one triangle
  });
  const auto want = brute_force(t, st);
  ++tally.triangles;
  tally.covered += want.size();
  for (const auto& p : model) tally.wrong += !want.count(p);
  for (const auto& p : want) tally.wrong += !model.count(p);
}

// Random (c, d) with a d - b c = 1 for coprime (a, b), by the extended Euclid algorithm.
std::pair<int64_t, int64_t> unimodular_partner(int64_t a, int64_t b) {
  int64_t r0 = a, r1 = b, s0 = 1, s1 = 0, t0 = 0, t1 = 1;
  while (r1 != 0) {
    const int64_t q = r0 / r1;
    std::tie(r0, r1) = std::make_pair(r1, r0 - q * r1);
    std::tie(s0, s1) = std::make_pair(s1, s0 - q * s1);
    std::tie(t0, t1) = std::make_pair(t1, t0 - q * t1);
  }
  // s0 a + t0 b = 1: (c, d) = (-t0, s0) gives a d - b c = a s0 + b t0 = 1.
  return {-t0, s0};
}

struct Kind { const char* row; int kind; };
// A format and viewport, and the traversal method ("" = tiled; else bbox, hierarchical,
// scanline_f32, scanline_f64, scanline_fixed).
struct FormatCase {
  const char* format;
  int viewport;
  std::string method = "";
};
void PrintTo(const FormatCase& c, std::ostream* os) {
  *os << c.format << " " << c.viewport << "x" << c.viewport << " " << (c.method.empty() ? "tiled" : c.method);
}

void set_method(RasterState& st, const std::string& m) {
  if (m == "bbox") st.traversal = Traversal::Bbox;
  if (m == "hierarchical") st.traversal = Traversal::Hierarchical, st.hier_levels = {64, 16, 4};
  if (m.rfind("scanline", 0) == 0) {
    st.traversal = Traversal::Scanline;
    st.scanline_arith = m == "scanline_f32" ? DdaArith::F32 : m == "scanline_f64" ? DdaArith::F64 : DdaArith::Fixed;
  }
}
bool exact_method(const std::string& m) { return m.rfind("scanline", 0) != 0; }

Tally run_kind(int kind, const FormatCase& fc, int count, uint64_t seed) {
  RasterState st = testing::stability_state(fc.format, fc.viewport, fc.viewport);
  set_method(st, fc.method);
  const int F = st.coord_format.frac_bits;
  const int64_t one = int64_t{1} << F, half_vp = int64_t(fc.viewport / 2) << F;
  const int64_t lim = st.coord_format.raw_max();  // stay inside the format
  std::mt19937_64 rng(seed);
  auto uni = [&](int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng); };
  auto inside = [&](const Tri& t) {
    for (const RawPt& p : t)
      for (int64_t c : p) if (c < st.coord_format.raw_min() || c > lim) return false;
    return true;
  };
  Tally tally;
  int made = 0;
  while (made < count) {
    Tri t;
    // A start point anywhere in the viewport plus a little guard band.
    const RawPt o = {uni(-half_vp - one, half_vp + one), uni(-half_vp - one, half_vp + one)};
    switch (kind) {
      case 0: {  // sliver of area 1 ulp^2: edge vectors (a, b), (c, d) with a d - b c = +-1;
                 // half of them start on a pixel centre, so the rule decides that sample
        const int64_t span = uni(1, int64_t(fc.viewport) * one);
        int64_t a = uni(1, span), b = uni(0, span);
        if (std::gcd(a, b) != 1) continue;
        auto [c, d] = unimodular_partner(a, b);
        const int64_t k = uni(-3, 3);  // shear along (a, b): area unchanged
        c += k * a, d += k * b;
        if (uni(0, 1)) std::swap(a, b), std::swap(c, d);  // mirror: area -1
        if (uni(0, 1)) a = -a, c = -c;                      // mirror in x: area -1
        RawPt s0 = o;
        if (uni(0, 1)) s0 = {(o[0] >> F << F) + one / 2, (o[1] >> F << F) + one / 2};
        t = {s0, RawPt{s0[0] + a, s0[1] + b}, RawPt{s0[0] + c, s0[1] + d}};
        break;
      }
      case 1: {  // collinear (incl. coincident) vertices: area 0
        const int64_t a = uni(-4 * one, 4 * one), b = uni(-4 * one, 4 * one), k = uni(-3, 3), m = uni(-3, 3);
        t = {o, RawPt{o[0] + k * a, o[1] + k * b}, RawPt{o[0] + m * a, o[1] + m * b}};
        break;
      }
      case 2: {  // vertices on tile corners, pixel corners and pixel centres
        for (RawPt& p : t)
          for (int64_t& c : p) {
            const int64_t px = uni(-fc.viewport / 2 - 2, fc.viewport / 2 + 2);
            switch (uni(0, 2)) {
              case 0: c = (px / 16) * 16 * one; break;  // tile corner (tile_size 16)
              case 1: c = px * one; break;              // pixel corner
              default: c = px * one + one / 2; break;   // pixel centre
            }
          }
        break;
      }
      default: {  // near-collinear: the third vertex one LSB off the line through two
        const int64_t a = uni(-8 * one, 8 * one), b = uni(-8 * one, 8 * one), k = uni(-2, 3);
        t = {o, RawPt{o[0] + a, o[1] + b}, RawPt{o[0] + k * a + uni(-1, 1), o[1] + k * b + uni(-1, 1)}};
        break;
      }
    }
    if (!inside(t)) continue;
    check(t, st, tally);
    ++made;
  }
  return tally;
}

class Degenerate : public ::testing::TestWithParam<FormatCase> {};

TEST_P(Degenerate, SameCoverageAsBruteForce) {
  const FormatCase fc = GetParam();
  const char* kinds[] = {"sliver 1 ulp", "collinear", "tile corners, pixel corners and centres", "near-collinear"};
  Tally tally[4];
  // Rows of the doc: "s7.16, sliver 1 ulp" for tiled, "s7.16 bbox, sliver 1 ulp" for the others.
  const std::string name = std::string(fc.format) + (fc.method.empty() ? "" : " " + fc.method);
  for (int kind = 0; kind < 4; ++kind) {
    tally[kind] = run_kind(kind, fc, 1500, 20261124 + kind);
    const Tally& t = tally[kind];
    std::printf("| %s, %s | %llu | %llu | %llu / %llu |\n", name.c_str(), kinds[kind], (unsigned long long)t.triangles,
                (unsigned long long)t.covered, (unsigned long long)t.wrong, (unsigned long long)t.outside);
  }
  for (int kind = 0; kind < 4; ++kind) {
    SCOPED_TRACE(kinds[kind]);
    const Tally& t = tally[kind];
    if (exact_method(fc.method)) {
      EXPECT_EQ(t.wrong, 0u) << "the model's coverage differs from the brute-force reference";
    }
    EXPECT_EQ(t.outside, 0u) << "fragments outside the framebuffer";
    const testing::DocRow row = testing::doc_row("Degenerate triangles", name + ", " + kinds[kind]);
    ASSERT_GE(row.size(), 4u);
    EXPECT_EQ(std::to_string(t.triangles), row[1]);
    EXPECT_EQ(std::to_string(t.covered), row[2]) << "the figure moved: update docs/stability.md and say why";
    EXPECT_EQ(std::to_string(t.wrong) + " / " + std::to_string(t.outside), row[3]);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, Degenerate,
                         ::testing::Values(FormatCase{"s7.16", 128}, FormatCase{"s4.4", 16},
                                           FormatCase{"s15.8", 128}),
                         [](const auto& info) {
                           std::string n = info.param.format;
                           for (char& c : n) if (c == '.') c = '_';
                           return n;
                         });

// Every other traversal method on the same triangles (s7.16): the exact ones must match
// the brute force; scanline's errors are counted and documented.
INSTANTIATE_TEST_SUITE_P(Methods, Degenerate,
                         ::testing::Values(FormatCase{"s7.16", 128, "bbox"}, FormatCase{"s7.16", 128, "hierarchical"},
                                           FormatCase{"s7.16", 128, "scanline_f32"},
                                           FormatCase{"s7.16", 128, "scanline_f64"},
                                           FormatCase{"s7.16", 128, "scanline_fixed"}),
                         [](const auto& info) { return info.param.method; });

// The reference itself, hand-worked: the right triangle (0,0), (2,0), (0,2) px in a 4x4
// viewport (origin 2,2). Centre (0.5,0.5) is strictly inside; (1.5,0.5) and (0.5,1.5)
// lie ON the hypotenuse x + y = 2, which runs down-left on the triangle's right side
// (neither top nor left), so they are out; (1.5,1.5) is outside. The top edge y = 0 and
// the left edge x = 0 pass through no centre.
TEST(DegenerateGolden, HandWorkedHypotenuse) {
  const RasterState st = testing::stability_state("s4.4", 4, 4);
  const int64_t one = 16;
  const Tri t = {RawPt{-2 * one, -2 * one}, RawPt{0, -2 * one}, RawPt{-2 * one, 0}};
  const auto got = brute_force(t, st);
  EXPECT_EQ(got, (std::set<std::pair<int, int>>{{0, 0}}));
}

}  // namespace
}  // namespace rastsim
