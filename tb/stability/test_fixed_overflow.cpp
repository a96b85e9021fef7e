// SPDX-License-Identifier: Apache-2.0
// Fixed-point overflow (docs/stability.md, "Fixed-point overflow"): for each format, the
// largest (and smallest) coordinate triangle setup accepts, found by binary search on
// the raw coordinate; at that bound the setup is exact and its edge values fit the
// derived width (datapath_widths), one LSB past it setup reports the vertex (culled as
// out_of_range, or a SceneError naming it), never a wrapped value.
//
// Viewport 1x1: the snapping origin is pixel (0, 0), so a coordinate in pixels is also
// its offset from the origin. The exactness check uses the largest triangle of the
// coordinate square, (max, max), (min, max), (max, min), whose edge value at the far
// corner (min, min) is L^2 with L = raw_max - raw_min = 2^(N+1) - 1 (docs/fixed-point.md):
// the model's EdgeEq values at the four corners must equal the cross products computed
// here in __int128, and L^2 must need exactly the derived edge width.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "ref/tri_setup.h"
#include "stability/doc_table.h"
#include "stability/stability_state.h"

namespace rastsim {
namespace {

SceneVertex vertex_raw(int64_t rx, int64_t ry, int frac_bits) {
  SceneVertex v;
  v.x.q = i128(rx) << (Q64::kFracBits - frac_bits);
  v.y.q = i128(ry) << (Q64::kFracBits - frac_bits);
  v.z = 0.5;
  return v;
}

// Setup of a probe triangle with one vertex at raw (x, y) and two beside the origin.
SetupOutcome probe(const RasterState& st, int64_t x, int64_t y) {
  const int F = st.coord_format.frac_bits;
  SetupTriangle t;
  return setup_triangle({vertex_raw(x, y, F), vertex_raw(0, 0, F), vertex_raw(0, 1, F)}, st, {"probe", 0}, t);
}

// Largest raw r in [0, 2^40) along direction (dx, dy) (unit steps of +-1) that setup does
// not report as out of range. Binary search: acceptance is monotone in |r|.
int64_t largest_accepted(const RasterState& st, int dx, int dy) {
  int64_t lo = 0, hi = int64_t{1} << 40;  // lo accepted, hi rejected
  EXPECT_NE(probe(st, 0, 0), SetupOutcome::CulledOutOfRange);
  EXPECT_EQ(probe(st, dx * hi, dy * hi), SetupOutcome::CulledOutOfRange);
  while (hi - lo > 1) {
    const int64_t mid = lo + (hi - lo) / 2;
    (probe(st, dx * mid, dy * mid) == SetupOutcome::CulledOutOfRange ? hi : lo) = mid;
  }
  return lo;
}

// raw / 2^F as an exact decimal (F <= 30: 30 fraction digits are enough).
std::string decimal(int64_t raw, int frac_bits) {
  const bool neg = raw < 0;
  const u128 mag = neg ? u128(-i128(raw)) : u128(raw);
  std::string s = (neg ? "-" : "") + to_string(i128(mag >> frac_bits));
  u128 frac = mag & ((u128(1) << frac_bits) - 1);
  if (frac == 0) return s;
  s += '.';
  while (frac) {
    frac *= 10;
    s += char('0' + int(frac >> frac_bits));
    frac &= (u128(1) << frac_bits) - 1;
  }
  return s;
}

class FixedOverflow : public ::testing::TestWithParam<const char*> {};

TEST_P(FixedOverflow, BoundIsExactAndOneStepPastIsReported) {
  RasterState st = testing::stability_state(GetParam(), 1, 1);
  const FixedFormat f = st.coord_format;
  const int F = f.frac_bits;
  const DatapathWidths w = datapath_widths(f, st.depth_bits);

  // The search, on both signs of both axes.
  const int64_t xmax = largest_accepted(st, 1, 0), ymax = largest_accepted(st, 0, 1);
  const int64_t xmin = -largest_accepted(st, -1, 0), ymin = -largest_accepted(st, 0, -1);
  EXPECT_EQ(xmax, ymax);
  EXPECT_EQ(xmin, ymin);

  // At the bound: exact. The largest triangle of the square, edge values at its corners.
  SetupTriangle t;
  ASSERT_EQ(setup_triangle({vertex_raw(xmax, xmax, F), vertex_raw(xmin, xmax, F), vertex_raw(xmax, xmin, F)}, st,
                           {"bound", 0}, t),
            SetupOutcome::Accepted);
  const std::array<std::array<int64_t, 2>, 3> v = {{{xmax, xmax}, {xmin, xmax}, {xmax, xmin}}};
  i128 max_abs_e = 0;
  for (int64_t cx : {xmin, xmax})
    for (int64_t cy : {xmin, xmax})
      for (int i = 0; i < 3; ++i) {
        // The exact cross product (v_j - v_i) x (c - v_i), sign-normalised by the orientation.
        const auto& a = v[i];
        const auto& b = v[(i + 1) % 3];
        const i128 cross = i128(b[0] - a[0]) * (cy - a[1]) - i128(b[1] - a[1]) * (cx - a[0]);
        const i128 e = t.edge[i].eval(cx, cy);
        EXPECT_TRUE(e == cross || e == -cross) << "corner (" << cx << ", " << cy << ") edge " << i;
        EXPECT_TRUE(fits_signed(e, w.edge)) << to_string(e) << " needs more than " << w.edge << " bits";
        EXPECT_TRUE(fits_signed(t.edge[i].c, w.edge));
        if ((e < 0 ? -e : e) > max_abs_e) max_abs_e = e < 0 ? -e : e;
      }
  const i128 L = i128(xmax) - xmin;
  EXPECT_EQ(max_abs_e, L * L);                     // the documented tight bound L^2
  EXPECT_EQ(signed_width(max_abs_e), w.edge);      // ... needs exactly the derived width
  EXPECT_EQ(t.area2, L * L);

  // One LSB past: reported, never wrapped: culled as out_of_range, or with
  // raster.out_of_range = error a SceneError naming the vertex.
  EXPECT_EQ(probe(st, xmax + 1, 0), SetupOutcome::CulledOutOfRange);
  EXPECT_EQ(probe(st, xmin - 1, 0), SetupOutcome::CulledOutOfRange);
  EXPECT_EQ(probe(st, 0, ymax + 1), SetupOutcome::CulledOutOfRange);
  st.out_of_range = OutOfRange::Error;
  try {
    probe(st, xmax + 1, 0);
    ADD_FAILURE() << "no error one LSB past the bound";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the " + f.name() + " coordinate range"), std::string::npos)
        << e.what();
  }

  std::printf("| %s | %s | %s | %d | %s |\n", f.name().c_str(), decimal(xmax, F).c_str(),
              decimal(xmin, F).c_str(), w.edge, to_string(max_abs_e).c_str());
  const testing::DocRow row = testing::doc_row("Fixed-point overflow", f.name());
  ASSERT_GE(row.size(), 5u);
  EXPECT_EQ(decimal(xmax, F), row[1]) << "the figure moved: update docs/stability.md and say why";
  EXPECT_EQ(decimal(xmin, F), row[2]);
  EXPECT_EQ(std::to_string(w.edge), row[3]);
  EXPECT_EQ(to_string(max_abs_e), row[4]);
}

// The shipped configs' formats (s7.16 default, s15.8 d3d11, s10.4 embedded, s12.8
// desktop), the smallest and the widest, and a few others.
INSTANTIATE_TEST_SUITE_P(Formats, FixedOverflow,
                         ::testing::Values("s7.16", "s15.8", "s10.4", "s12.8", "s1.1", "s4.4", "s15.16", "s20.11",
                                           "s1.30", "s30.1"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n) if (c == '.') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace rastsim
