// SPDX-License-Identifier: Apache-2.0
// `rastsim fit` (ref/study/coord_fit.h): on the shipped traces and on generated scenes, the
// fitted format renders identically to the widest format with the same integer bits
// (I + F = 31), one fraction bit fewer does not (unless F is already the smallest, 1),
// and one integer bit fewer is rejected or renders differently. Independent goldens: a
// scene whose vertices all lie on the 2^-k grid snaps exactly at F = k, so its fit can be
// no wider than k; integer vertices fit at F = 1 and are exact at 0 fraction bits; the
// widths of s7.16 are the hand-worked column of docs/fixed-point.md.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>

#include "common/default_state.h"
#include "config/raster_state_config.h"
#include "ref/study/coord_fit.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using testing_common::default_state;

// Checks the three properties of a fit; returns it.
CoordFit check_fit(const Scene& scene, const RasterState& arch) {
  const CoordFit fit = fit_coord_format(scene, arch);
  EXPECT_EQ(fit.format.int_bits, fit.widest.int_bits);
  EXPECT_EQ(fit.widest.int_bits + fit.widest.frac_bits, kMaxFormatBits);
  EXPECT_EQ(fit.widths, datapath_widths(fit.format, arch.depth_bits));
  RasterState st = arch;
  st.coord_format = fit.format;
  EXPECT_TRUE(render_signature(scene, st).same_as(fit.reference)) << "the fit renders differently";
  if (fit.format.frac_bits > 1) {
    st.coord_format = FixedFormat{fit.format.int_bits, fit.format.frac_bits - 1};
    EXPECT_FALSE(render_signature(scene, st).same_as(fit.reference)) << st.coord_format.name() << " also fits";
  }
  if (fit.format.int_bits > 0) {
    st.coord_format = FixedFormat{fit.format.int_bits - 1, fit.format.frac_bits};
    const RenderSignature fewer = render_signature(scene, st);
    EXPECT_TRUE(!fewer.ok || !fewer.same_as(fit.reference)) << st.coord_format.name() << " holds the scene";
  }
  return fit;
}

class FitShippedTrace : public ::testing::TestWithParam<const char*> {};

TEST_P(FitShippedTrace, IdenticalAtTheFitNotOneBitNarrower) {
  const RasterState arch = default_state();
  const Scene scene = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/" + GetParam(), ObjPlacement{});
  const CoordFit fit = check_fit(scene, arch);
  std::printf("%s: %s (reference %s)\n", GetParam(), fit.format.name().c_str(), fit.widest.name().c_str());
  EXPECT_EQ(fit.int_bits_viewport, 7);  // a 128-px viewport: 2^(I+1) - 2 >= 128 first at I = 7
}

INSTANTIATE_TEST_SUITE_P(Traces, FitShippedTrace,
                         ::testing::Values("torus.trace", "primitives.trace", "fill_rule.trace", "state.trace"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.')) == "fill_rule" ? std::string("FillRule")
                                                                          : n.substr(0, n.find('.'));
                         });

// Random triangles with vertices on the 2^-k pixel grid (as exact decimals), inside the
// 128-px viewport.
Scene grid_scene(int k, uint64_t seed, int triangles) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int64_t> c(0, (int64_t{128} << k));
  std::ostringstream os;
  os << "viewport 128 128\nclear 0 0 0\n";
  auto dec = [&](int64_t raw) {
    // raw / 2^k exactly: 2^-k = 5^k / 10^k.
    int64_t p5 = 1;
    for (int j = 0; j < k; ++j) p5 *= 5;
    const std::string digits = std::to_string((raw & ((int64_t{1} << k) - 1)) * p5);
    return std::to_string(raw >> k) + (k ? "." + std::string(k - digits.size(), '0') + digits : "");
  };
  for (int t = 0; t < triangles; ++t) {
    os << "tri";
    for (int i = 3 * t; i < 3 * t + 3; ++i)
      os << " " << dec(c(rng)) << " " << dec(c(rng)) << " 0.5 " << (i * 37) % 256 << " " << (i * 91) % 256 << " "
         << (i * 13) % 256;
    os << "\n";
  }
  return parse_trace(os.str(), "grid" + std::to_string(k));
}

TEST(FitGenerated, GridScenesFitNoWiderThanTheirGrid) {
  const RasterState arch = default_state();
  for (int k : {1, 2, 3, 5, 8}) {
    SCOPED_TRACE(k);
    const CoordFit fit = check_fit(grid_scene(k, 100 + k, 40), arch);
    EXPECT_EQ(fit.format.int_bits, 7);
    EXPECT_LE(fit.format.frac_bits, std::max(k, 1));  // snapping is exact at F = k
    EXPECT_FALSE(fit.exact_at_zero_frac);             // the grid has half pixels: k >= 1
  }
}

TEST(FitGenerated, IntegerVerticesAreExactAtZeroFractionBits) {
  const RasterState arch = default_state();
  const CoordFit fit = check_fit(grid_scene(0, 7, 40), arch);
  EXPECT_EQ(fit.format.name(), "s7.1");
  EXPECT_TRUE(fit.exact_at_zero_frac);
}

TEST(FitGenerated, GuardBandVerticesNeedMoreIntegerBits) {
  // A vertex at x = -100 px in a 128-px viewport is 164 px left of the centre (64):
  // s7 holds [-128, 128), s8 [-256, 256).
  const RasterState arch = default_state();
  const Scene scene = parse_trace("viewport 128 128\ntri -100 10 0.5 255 0 0  50 10 0.5 0 255 0  50 60 0.5 0 0 255\n",
                                  "guard");
  const CoordFit fit = check_fit(scene, arch);
  EXPECT_EQ(fit.int_bits_vertices, 8);
  EXPECT_EQ(fit.format.int_bits, 8);
}

TEST(FitGenerated, WidthsOfS7_16AreTheDocumentedOnes) {
  // docs/fixed-point.md, "Datapath widths", s7.16 column (N = 23, D = 24).
  const DatapathWidths w = datapath_widths(FixedFormat::parse("s7.16"), 24);
  EXPECT_EQ(w.coord, 24);
  EXPECT_EQ(w.coef, 25);
  EXPECT_EQ(w.edge, 49);
  EXPECT_EQ(w.area, 48);
  EXPECT_EQ(w.color_num, 56);
  EXPECT_EQ(w.depth_num, 72);
}

TEST(FitGenerated, ClosedMeshDetection) {
  // One triangle is not closed (each edge used once); the torus is.
  EXPECT_FALSE(is_closed_mesh(parse_trace("tri 0 0 4 0 0 4\n", "one")));
  EXPECT_TRUE(is_closed_mesh(load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace", ObjPlacement{})));
}

// fit_recip on the clip-space cube: every triangle the near plane cuts has unequal 1/w;
// for each Newton-Raphson step count the fitted seed width renders as exact and one bit
// fewer does not (checked by rendering here); texture coordinates run 0..1 (the trace's
// texcoord values), so one integer bit (2^1 > 1). A screen-space scene takes no reciprocal.
TEST(FitRecip, FewestSeedBitsRenderAsExactOneFewerDoNot) {
  const RasterState arch = default_state();
  const Scene cube = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/3d/clip_cube.trace", ObjPlacement{});
  const RecipFit fit = fit_recip(cube, arch);
  EXPECT_GT(fit.perspective_triangles, 0u);
  EXPECT_EQ(fit.perspective_triangles, fit.triangles);
  EXPECT_EQ(fit.max_abs_texcoord, 1.0);
  EXPECT_EQ(fit.texcoord_int_bits, 1);
  RasterState st = arch;
  st.recip = RecipMethod::Newton;
  int found = 0;
  for (int it = 0; it <= kRecipFitIterations; ++it) {
    const int b = fit.seed_bits[size_t(it)];
    SCOPED_TRACE("iterations " + std::to_string(it) + ", seed bits " + std::to_string(b));
    st.recip_iterations = it;
    if (b == 0) continue;  // none up to 16 bits
    ++found;
    st.recip_seed_bits = b;
    EXPECT_TRUE(render_signature(cube, st).same_as(fit.exact));
    if (b > 1) {
      st.recip_seed_bits = b - 1;
      EXPECT_FALSE(render_signature(cube, st).same_as(fit.exact));
    }
  }
  EXPECT_GE(found, 3);  // more steps need fewer seed bits: at least 2..4 steps find a width
  const RecipFit torus = fit_recip(load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace", ObjPlacement{}), arch);
  EXPECT_EQ(torus.perspective_triangles, 0u);
  EXPECT_EQ(torus.seed_bits, (std::array<int, kRecipFitIterations + 1>{}));
}

}  // namespace
}  // namespace rastsim
