// SPDX-License-Identifier: Apache-2.0
// Exact area coverage (model/aa/exact_coverage.h): hand-worked pixels, the coverages of
// every pixel of a random triangle summing to its shoelace area, the integer fast path
// agreeing with the rational clip, and the one-sample mask being the centre test.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "aa/exact_coverage.h"
#include "config/raster_state_config.h"
#include "ref/fine_raster.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"

namespace rastsim {
namespace {

// A 16 x 16 viewport and framebuffer with the default config's s7.16 coordinates.
RasterState small_state(int size = 16, const char* fmt = "s7.16") {
  RasterState st = raster_state_from_config(Config{});
  st.coord_format = FixedFormat::parse(fmt);
  st.fb_width = st.fb_height = size;
  st.viewport_width = st.viewport_height = size;
  st.cull = CullMode::None;
  return st;
}

SceneVertex vertex(const char* x, const char* y) { return {Q64::parse_decimal(x), Q64::parse_decimal(y)}; }

SetupTriangle set_up(const RasterState& st, std::array<SceneVertex, 3> v) {
  SetupTriangle t;
  const SetupOutcome o = setup_triangle(v, st, SourceLoc{"test", 1}, t);
  EXPECT_EQ(o, SetupOutcome::Accepted);
  return t;
}

TEST(ExactCoverage, HandWorkedPixels) {
  const RasterState st = small_state();
  const int F = st.coord_format.frac_bits;
  // Legs on x = 0 and y = 0, hypotenuse x + y = 8: pixel (3, 4) spans x + y in [7, 9] and
  // the hypotenuse is its diagonal.
  const SetupTriangle big = set_up(st, {vertex("0", "0"), vertex("8", "0"), vertex("0", "8")});
  EXPECT_EQ(exact_pixel_coverage(big, 3, 4, F), mpq_class(1, 2));
  EXPECT_EQ(exact_pixel_coverage(big, 0, 7, F), mpq_class(1, 2));
  EXPECT_EQ(exact_pixel_coverage(big, 1, 1, F), mpq_class(1));      // inside
  EXPECT_EQ(exact_pixel_coverage(big, 6, 6, F), mpq_class(0));      // beyond the hypotenuse
  EXPECT_EQ(exact_pixel_coverage(big, 8, 0, F), mpq_class(0));      // touches a vertex only
  EXPECT_EQ(exact_pixel_coverage(big, 4, 4, F), mpq_class(0));      // touches the hypotenuse at a corner
  EXPECT_EQ(classify_pixel_square(big, 1, 1, F), SquareClass::Inside);
  EXPECT_EQ(classify_pixel_square(big, 6, 6, F), SquareClass::Outside);
  EXPECT_EQ(classify_pixel_square(big, 3, 4, F), SquareClass::Boundary);
  // A right triangle of legs 1/2 inside pixel (5, 5): 1/8.
  const SetupTriangle small = set_up(st, {vertex("5.25", "5.25"), vertex("5.75", "5.25"), vertex("5.25", "5.75")});
  EXPECT_EQ(exact_pixel_coverage(small, 5, 5, F), mpq_class(1, 8));
  EXPECT_EQ(exact_pixel_coverage(small, 4, 5, F), mpq_class(0));
  // A triangle covering the pixel whole, in the other winding, and one far outside it.
  const SetupTriangle cover = set_up(st, {vertex("1", "1"), vertex("1", "15"), vertex("15", "1")});
  EXPECT_EQ(exact_pixel_coverage(cover, 2, 2, F), mpq_class(1));
  EXPECT_EQ(exact_pixel_coverage(cover, 14, 14, F), mpq_class(0));
  // A vertex inside the pixel: the square [2, 3]^2 cut by x + y = 5.5 keeps 1 - 1/8.
  const SetupTriangle corner = set_up(st, {vertex("0", "0"), vertex("5.5", "0"), vertex("0", "5.5")});
  EXPECT_EQ(exact_pixel_coverage(corner, 2, 2, F), mpq_class(7, 8));
}

TEST(ExactCoverage, RawSquareAreaEitherWinding) {
  // Triangle (0,0) (4,0) (0,4) on the square [1, 3]^2: the square minus the corner above
  // x + y = 4, area 4 - 2 = 2.
  EXPECT_EQ(exact_square_area({0, 4, 0}, {0, 0, 4}, 1, 1, 2), mpq_class(2));
  EXPECT_EQ(exact_square_area({0, 0, 4}, {0, 4, 0}, 1, 1, 2), mpq_class(2));
  EXPECT_EQ(exact_square_area({0, 4, 0}, {0, 0, 4}, 10, 10, 2), mpq_class(0));
  // Triangle (0,0) (3,1) (0,1) on [0, 1]^2: {0 <= y <= 1, 0 <= x <= min(1, 3y)}, area
  // 1/6 + 2/3.
  EXPECT_EQ(exact_square_area({0, 3, 0}, {0, 1, 1}, 0, 0, 1), mpq_class(5, 6));
}

mpq_class shoelace(const SetupTriangle& t) {
  mpz_class twice = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    twice += mpz_class(std::to_string(t.x[i])) * mpz_class(std::to_string(t.y[j])) -
             mpz_class(std::to_string(t.x[j])) * mpz_class(std::to_string(t.y[i]));
  }
  mpq_class area(abs(twice), 2);
  area.canonicalize();  // a (numerator, denominator) pair is not reduced by itself
  return area;
}

struct SumCase {
  const char* fmt;
  int triangles;
  double max_size;  // px
  uint64_t seed;
};

class CoverageSum : public ::testing::TestWithParam<SumCase> {};

// Over every pixel under a random triangle, the exact coverages sum to its area in
// pixels (shoelace of the snapped vertices / 2^(2F)); each pixel's integer class agrees
// with its clipped coverage. A coarse format puts many vertices on pixel corners and edges.
TEST_P(CoverageSum, EqualsShoelaceArea) {
  const SumCase& c = GetParam();
  const RasterState st = small_state(64, c.fmt);
  const int F = st.coord_format.frac_bits;
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<double> pos(1.0, 63.0), off(-c.max_size, c.max_size);
  int done = 0;
  uint64_t boundary = 0;
  while (done < c.triangles) {
    const double cx = pos(rng), cy = pos(rng);
    std::array<SceneVertex, 3> v;
    for (auto& p : v) p = {Q64::from_double(std::clamp(cx + off(rng), 0.0, 64.0)), Q64::from_double(std::clamp(cy + off(rng), 0.0, 64.0))};
    SetupTriangle t;
    if (setup_triangle(v, st, SourceLoc{"random", done}, t) != SetupOutcome::Accepted) continue;
    ++done;
    const PixelRect r = pixels_under_triangle(t, F);
    mpq_class sum = 0;
    for (int py = r.y0; py < r.y1; ++py)
      for (int px = r.x0; px < r.x1; ++px) {
        const mpq_class f = exact_pixel_coverage(t, px, py, F);
        ASSERT_GE(f, 0);
        ASSERT_LE(f, 1);
        const SquareClass cls = classify_pixel_square(t, px, py, F);
        if (cls == SquareClass::Inside) {
          ASSERT_EQ(f, 1) << px << "," << py;
        } else if (cls == SquareClass::Outside) {
          ASSERT_EQ(f, 0) << px << "," << py;
        } else {
          ASSERT_LT(f, 1) << px << "," << py;
          ++boundary;
        }
        sum += f;
      }
    // One pixel beyond the box on every side is empty.
    EXPECT_EQ(exact_pixel_coverage(t, r.x0 - 1, r.y0, F), 0);
    EXPECT_EQ(exact_pixel_coverage(t, r.x1, r.y1 - 1, F), 0);
    const mpq_class one_px = mpq_class(mpz_class(1) << (2 * F));
    ASSERT_EQ(sum, shoelace(t) / one_px) << "triangle " << done;
  }
  EXPECT_GT(boundary, uint64_t(c.triangles));  // the clip did run
}

INSTANTIATE_TEST_SUITE_P(Random, CoverageSum,
                         ::testing::Values(SumCase{"s7.16", 300, 6.0, 1}, SumCase{"s7.16", 100, 1.0, 2},
                                           SumCase{"s7.2", 300, 5.0, 3}, SumCase{"s7.1", 200, 3.0, 4}),
                         [](const auto& info) { return "case" + std::to_string(info.index); });

// With one sample the traversal's mask is the centre test, pixel by pixel.
TEST(OneSample, MaskIsTheCentreTest) {
  RasterState st = small_state(64);
  st.samples = 1;
  const int F = st.coord_format.frac_bits;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-4.0, 68.0);
  for (int n = 0; n < 300; ++n) {
    std::array<SceneVertex, 3> v;
    for (auto& p : v) p = {Q64::from_double(pos(rng)), Q64::from_double(pos(rng))};
    SetupTriangle t;
    if (setup_triangle(v, st, SourceLoc{"random", n}, t) != SetupOutcome::Accepted) continue;
    std::vector<uint32_t> mask(64 * 64, 0);
    TraversalCounters c;
    traverse(t, traversal_params(st), c, [&](int px, int py, uint32_t m) { mask[size_t(py * 64 + px)] = m; });
    for (int py = 0; py < 64; ++py)
      for (int px = 0; px < 64; ++px) {
        const bool centre = pixel_covered(t, px, py, F);
        ASSERT_EQ(mask[size_t(py * 64 + px)], centre ? 1u : 0u) << n << ": " << px << "," << py;
        ASSERT_EQ(pixel_sample_mask(t, px, py, F), centre ? 1u : 0u);
      }
  }
}

}  // namespace
}  // namespace rastsim
