// SPDX-License-Identifier: Apache-2.0
// Where the speed-against-accuracy methods of perspective interpolation fail
// (docs/clip-space.md, "Where methods fail"), each kept as a test of both sides:
//
// - Affine interpolation (interp.perspective = false) against perspective-correct, on a
//   plane that fills the view and recedes in depth: its near (bottom) edge at w = 1, its
//   far (top) edge at w = r. The first ratio r whose texture coordinate error reaches
//   one texel of a 256-texel texture mapped once across the plane, found by a scan and
//   checked against the projection worked in long double here.
// - A low-precision newton reciprocal (interp.recip_seed_bits = 4, two Newton-Raphson
//   steps) against interp.recip = exact on the same plane: the first ratio r at which a
//   texture coordinate differs from exact's by more than one LSB. (With one step every
//   seed width up to 8 bits errs by more than one LSB at the first ratio scanned,
//   1 + 1/256: DISABLED_RecipScan.)
//
// The plane is a clip-space scene built here (two tri4 triangles through the whole
// pipeline, front end included): corners (x, y, z, w) = (-1, 1, 0.5, 1), (1, 1, 0.5, 1)
// at the bottom of a 64 x 64 viewport and (-r, -r, 0.5 r, r), (r, -r, 0.5 r, r) at its
// top (NDC y = -1 is the top row), so it covers the viewport exactly; the four corners
// are coplanar (y = (2 r - (1 + r) w) / (r - 1) at each, x free), a floor seen from
// above whose far edge is r times as deep as its near edge (r -> infinity: the horizon).
// s runs 0..1 left to right, t 0..1 near to far, colour 0..255 near to far in red.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "ref/study/recip_grid.h"

namespace rastsim {
namespace {

constexpr int kSize = 64;           // viewport, px
constexpr int kTexFrac = 20;        // the default interp.texcoord_format, s7.20: LSBs a repeat 2^20
constexpr int kTexels = 256;        // texels across the texture (one repeat across the plane)
constexpr int64_t kLsbPerTexel = (int64_t{1} << kTexFrac) / kTexels;

RasterState plane_state() {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.viewport_width = kSize;
  st.fb_height = st.viewport_height = kSize;
  st.cull = CullMode::None;
  st.perspective = true;
  st.recip = RecipMethod::Exact;
  return st;
}

// The plane with far-edge depth ratio r (r exact in binary32: the scans step by 2^-k).
Scene plane_scene(float r) {
  const auto corner = [](float x, float y, float w, uint8_t red, float s, float t) {
    ClipVertex v;
    v.x = x, v.y = y, v.z = 0.5f * w, v.w = w;
    v.r = red, v.g = 0, v.b = 0;
    v.s = s, v.t = t;
    return v;
  };
  const ClipVertex bl = corner(-1, 1, 1, 0, 0, 0), br = corner(1, 1, 1, 0, 1, 0);
  const ClipVertex tl = corner(-r, -r, r, 255, 0, 1), tr = corner(r, -r, r, 255, 1, 1);
  CmdPrimitives prims;
  prims.topology = Topology::List;
  prims.clip_vertices = {bl, br, tr, bl, tr, tl};
  Scene scene;
  scene.source = "plane";
  scene.commands.push_back(Command{CmdViewport{kSize, kSize}, SourceLoc{"plane", 1}});
  scene.commands.push_back(Command{prims, SourceLoc{"plane", 2}});
  return scene;
}

std::vector<Fragment> fragments_of(const Scene& scene, const RasterState& st) {
  std::vector<Fragment> out;
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) { out.push_back(f); });
  return out;
}

// Largest |s - s'|, |t - t'| (raw LSBs) between two renders of the same fragments.
int64_t max_texcoord_difference(const std::vector<Fragment>& a, const std::vector<Fragment>& b) {
  EXPECT_EQ(a.size(), b.size());
  int64_t m = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    EXPECT_TRUE(a[i].x == b[i].x && a[i].y == b[i].y) << "fragment " << i;
    m = std::max({m, std::abs(int64_t(a[i].s) - b[i].s), std::abs(int64_t(a[i].t) - b[i].t)});
  }
  return m;
}

// ---- Affine against perspective ----

// The projection in long double: at a pixel centre's row j, the fraction of the way up
// the screen from the near edge is u = 1 - (j + 1/2) / 64; affine t is u itself, the
// perspective-correct t is the point of the plane seen there: 1/w is affine in screen
// space (1 at u = 0, 1/r at u = 1) and t/w too (0 and 1/r), so t = (u / r) / (1 - u +
// u / r). s is the same both ways (every row has one w). The largest difference over
// the rows, in texels.
long double affine_error_texels(long double r) {
  long double m = 0;
  for (int j = 0; j < kSize; ++j) {
    const long double u = 1.0L - (j + 0.5L) / kSize;
    const long double persp = (u / r) / (1.0L - u + u / r);
    m = std::max(m, std::fabs(u - persp) * kTexels);
  }
  return m;
}

// The model's affine error on the plane, in texels.
double model_affine_error_texels(float r) {
  RasterState st = plane_state();
  const Scene scene = plane_scene(r);
  const std::vector<Fragment> persp = fragments_of(scene, st);
  st.perspective = false;
  const std::vector<Fragment> affine = fragments_of(scene, st);
  EXPECT_EQ(persp.size(), size_t(kSize * kSize));  // the plane covers the viewport
  return double(max_texcoord_difference(persp, affine)) / double(kLsbPerTexel);
}

// The scan's step in r, and the first step whose projected error reaches a texel (found
// by AffineBreaksAtOneTexel's scan; the closed form below puts it at 1.0157).
constexpr float kRatioStep = 1.0f / 4096;
constexpr int kAffineFirstStep = 65;

TEST(FailurePoints, AffineBreaksAtOneTexel) {
  // Closed form (hand-worked): over continuous u the largest |u - t| is (sqrt r - 1) /
  // (sqrt r + 1), at u = sqrt r / (sqrt r + 1); a texel of 256 at sqrt r = 257 / 255.
  const long double closed = (257.0L / 255.0L) * (257.0L / 255.0L);
  EXPECT_NEAR(affine_error_texels(closed), 1.0L, 1e-3L);
  int first = 0;
  for (int k = 1; k <= 4096 && !first; ++k)
    if (affine_error_texels(1.0L + k * (long double)kRatioStep) >= 1.0L) first = k;
  const float below = 1.0f + (kAffineFirstStep - 1) * kRatioStep, above = 1.0f + kAffineFirstStep * kRatioStep;
  const double model_below = model_affine_error_texels(below), model_above = model_affine_error_texels(above);
  std::cout << "affine breaks a texel of " << kTexels << " at depth ratio " << above << " (projection "
            << double(affine_error_texels(above)) << " texels, model " << model_above << "); at " << below
            << ": projection " << double(affine_error_texels(below)) << ", model " << model_below << "\n";
  EXPECT_EQ(first, kAffineFirstStep);
  // The model agrees with the projection to within its rounding: each texture
  // coordinate rounds to 2^-20 of a repeat (1/4096 texel), 1/w to binary32.
  EXPECT_NEAR(model_below, double(affine_error_texels(below)), 2.0 / double(kLsbPerTexel));
  EXPECT_NEAR(model_above, double(affine_error_texels(above)), 2.0 / double(kLsbPerTexel));
  EXPECT_LT(model_below, 1.0);
  EXPECT_GE(model_above, 1.0);
}

// ---- A low-precision reciprocal against exact ----

// The setting, the scan's step in r and its first step past one LSB (found by the scan
// below; 1 + 120/256 = 1.46875).
constexpr int kLowSeedBits = 4, kLowIterations = 2;
constexpr float kRecipRatioStep = 1.0f / 256;
constexpr int kRecipFirstStep = 120;

// The largest |newton - exact| in LSBs over the plane's s, t with a newton setting.
int64_t recip_error(float r, int seed_bits = kLowSeedBits, int iterations = kLowIterations) {
  RasterState st = plane_state();
  const Scene scene = plane_scene(r);
  const std::vector<Fragment> exact = fragments_of(scene, st);
  st.recip = RecipMethod::Newton;
  st.recip_seed_bits = seed_bits;
  st.recip_iterations = iterations;
  return max_texcoord_difference(exact, fragments_of(scene, st));
}
int64_t low_recip_error(float r) { return recip_error(r); }

// The scan behind the choice of setting (run by hand: --gtest_also_run_disabled_tests
// --gtest_filter='*RecipScan'): for each setting, the first ratio 1 + k/256 whose
// error passes one LSB, and the error there.
TEST(FailurePoints, DISABLED_RecipScan) {
  for (const auto& [b, it] : {std::pair{4, 1}, {6, 1}, {8, 1}, {10, 1}, {12, 1}, {4, 2}, {6, 2}}) {
    int first = 0;
    int64_t e = 0;
    for (int k = 1; k <= 16 * 256 && !first; ++k)
      if ((e = recip_error(1.0f + float(k) / 256, b, it)) > 1) first = k;
    std::cout << b << " bits " << it << " steps: first > 1 LSB at r = " << (first ? 1.0 + first / 256.0 : 0.0)
              << " (" << e << " LSB)\n";
  }
}

TEST(FailurePoints, LowPrecisionReciprocalErrsPastOneLsb) {
  int first = 0;
  for (int k = 1; k <= 16 * 256 && !first; ++k)
    if (low_recip_error(1.0f + k * kRecipRatioStep) > 1) first = k;
  const float below = 1.0f + (kRecipFirstStep - 1) * kRecipRatioStep, above = 1.0f + kRecipFirstStep * kRecipRatioStep;
  std::cout << "newton " << kLowSeedBits << " seed bits, " << kLowIterations << " steps: first errs by > 1 LSB at depth ratio "
            << above << " (" << low_recip_error(above) << " LSB; " << low_recip_error(below) << " at " << below << ")\n";
  EXPECT_EQ(first, kRecipFirstStep);
  EXPECT_LE(low_recip_error(below), 1);
  EXPECT_GT(low_recip_error(above), 1);
}

// ---- rastsim recip-grid's rows (ref/study/recip_grid.h) ----

// On the plane at r = 2, each row's texture coordinate figures equal a comparison of
// the two fragment streams made here, and colour is counted apart (3 values a fragment
// against 2); interp.recip = exact at 16 bits and 4 steps would differ from newton only
// within 1 LSB (docs/clip-space.md), 4 bits and 0 steps by far more.
TEST(RecipGrid, RowsMatchADirectComparison) {
  const Scene scene = plane_scene(2.0f);
  const RecipGrid g = recip_grid(scene, plane_state(), 16, 4);
  ASSERT_EQ(g.rows.size(), 16u * 5);
  EXPECT_EQ(g.fragments, uint64_t(kSize * kSize));
  for (const RecipGridRow& row : g.rows) {
    if (row.seed_bits % 4 != 0) continue;  // a quarter of the rows: the check is the same
    SCOPED_TRACE(std::to_string(row.seed_bits) + " bits " + std::to_string(row.iterations) + " steps");
    EXPECT_EQ(row.colour.values, 3 * g.fragments);
    EXPECT_EQ(row.texcoord.values, 2 * g.fragments);
    EXPECT_EQ(int64_t(row.texcoord.max), recip_error(2.0f, row.seed_bits, row.iterations));
    EXPECT_EQ(row.exact(), row.colour.wrong == 0 && row.texcoord.wrong == 0);
  }
  EXPECT_GT(g.rows[3].texcoord.max, 1000u);  // 4 bits, 0 steps
  EXPECT_LE(g.rows.back().texcoord.max, 1u);  // 16 bits, 4 steps
}

}  // namespace
}  // namespace rastsim
