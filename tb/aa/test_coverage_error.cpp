// SPDX-License-Identifier: Apache-2.0
// The coverage-error study (model/aa/coverage_error.h): hand-worked scenes whose every
// mask and coverage can be counted on paper, then the figures of the four traces/aa
// scenes against the table of docs/results.md ("Anti-aliasing: coverage error").
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "aa/coverage_error.h"
#include "results_doc.h"
#include "common/default_state.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using testing_common::default_state;

const std::vector<int> kCounts = {1, 2, 4, 8, 16};

// Hypotenuse x + y = 8 through the diagonals of the pixels (i, 7 - i), i = 0..7: f = 1/2,
// the centre on the edge (sum 8). A sample at offset (dx, dy)/16 is covered when
// dx + dy < 0 (the hypotenuse is a right edge, excluded by the top-left rule); the legs
// lie on x = 0 and y = 0 (left and top edges, included), so every other pixel is exact.
// Covered samples: 1x 0 of 1 (centre on the edge), 2x 1 of 2, 4x 2 of 4 (sums -8, 4, -4,
// 8), 8x 3 of 8 (sums -2, 2, 6, -8, 0, -8, 10, 0), 16x 9 of 16. Drawn twice: per triangle.
TEST(CoverageError, DiagonalHandWorked) {
  const Scene scene = parse_trace("viewport 128 128\ntri 0 0 8 0 0 8\ntri 0 0 8 0 0 8\n", "diag.trace");
  const CoverageErrorResult r = measure_coverage_error(scene, default_state(), kCounts);
  const double want[] = {0.5, 0.0, 0.0, 1.0 / 8, 1.0 / 16};
  ASSERT_EQ(r.per_samples.size(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    SCOPED_TRACE(kCounts[i]);
    const CoverageErrorStats& s = r.per_samples[i];
    EXPECT_EQ(s.samples, kCounts[i]);
    EXPECT_EQ(s.triangles, 2u);
    EXPECT_EQ(s.edge_pixels, 16u);
    EXPECT_DOUBLE_EQ(s.mean(), want[i]);
    EXPECT_DOUBLE_EQ(s.rms(), want[i]);
    EXPECT_DOUBLE_EQ(s.error_max, want[i]);
  }
  EXPECT_EQ(r.pixels_clipped, 8u + 8u);  // the diagonal pixels, once a triangle (corner touches are exact)
}

// A right triangle of legs 1/4 in pixel (5, 5), area 1/32, between the centre and every
// sample but one of 16x ((-4, -6) sits on its top edge, included): 1x, 4x and 8x miss it
// (1x: setup finds no sample in its box and culls it; still measured), 16x covers 1/16.
TEST(CoverageError, SubPixelTriangle) {
  const Scene scene = parse_trace("viewport 128 128\ntri 5.125 5.125 5.375 5.125 5.125 5.375\n", "tiny.trace");
  const CoverageErrorResult r = measure_coverage_error(scene, default_state(), {1, 4, 8, 16});
  for (const CoverageErrorStats& s : r.per_samples) {
    SCOPED_TRACE(s.samples);
    EXPECT_EQ(s.triangles, 1u);
    EXPECT_EQ(s.edge_pixels, 1u);
    EXPECT_DOUBLE_EQ(s.error_max, 1.0 / 32);
  }
}

// The exact traversals emit the same masks (docs/traversal.md), so the same figures.
TEST(CoverageError, SameForEveryExactTraversal) {
  const Scene scene = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/aa/thin.trace", ObjPlacement{});
  RasterState st = default_state();
  const CoverageErrorResult tiled = measure_coverage_error(scene, st, kCounts);
  for (Traversal m : {Traversal::Bbox, Traversal::Hierarchical}) {
    st.traversal = m;
    const CoverageErrorResult r = measure_coverage_error(scene, st, kCounts);
    for (size_t i = 0; i < kCounts.size(); ++i) {
      EXPECT_EQ(r.per_samples[i].edge_pixels, tiled.per_samples[i].edge_pixels);
      EXPECT_EQ(r.per_samples[i].error_sum, tiled.per_samples[i].error_sum);
      EXPECT_EQ(r.per_samples[i].error_max, tiled.per_samples[i].error_max);
    }
  }
}

TEST(CoverageError, RejectsBadCounts) {
  const Scene scene = parse_trace("viewport 128 128\ntri 0 0 8 0 0 8\n", "diag.trace");
  EXPECT_THROW(measure_coverage_error(scene, default_state(), {3}), std::invalid_argument);
  RasterState st = default_state();
  st.traversal = Traversal::Scanline;
  EXPECT_THROW(measure_coverage_error(scene, st, {4}), std::invalid_argument);
  EXPECT_NO_THROW(measure_coverage_error(scene, st, {1}));
}

// Every row of the doc's table, recomputed (configs/default.toml, the scene's own
// raster.samples overridden). Figures are printed to 4 decimals.
TEST(CoverageError, AaScenesMatchDocsResults) {
  const std::vector<aa_test::TableRow> rows = aa_test::results_table("Anti-aliasing: coverage error");
  std::map<std::string, CoverageErrorResult> by_scene;
  for (const aa_test::TableRow& row : rows) {
    const std::string scene = row.at("scene");
    SCOPED_TRACE(scene + " " + row.at("samples"));
    if (!by_scene.count(scene)) {
      const Scene s = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/aa/" + scene + ".trace", ObjPlacement{});
      by_scene[scene] = measure_coverage_error(s, default_state(), kCounts);
    }
    const int n = std::stoi(row.at("samples"));
    const CoverageErrorStats* got = nullptr;
    for (const CoverageErrorStats& s : by_scene[scene].per_samples)
      if (s.samples == n) got = &s;
    ASSERT_NE(got, nullptr) << "samples " << n;
    EXPECT_EQ(std::to_string(got->edge_pixels), row.at("edge pixels")) << "update docs/results.md and say why";
    auto near = [](double v, const std::string& doc) { return std::fabs(v - std::stod(doc)) <= 0.5e-4 + 1e-12; };
    EXPECT_TRUE(near(got->mean(), row.at("mean"))) << got->mean() << " vs " << row.at("mean");
    EXPECT_TRUE(near(got->rms(), row.at("RMS"))) << got->rms() << " vs " << row.at("RMS");
    EXPECT_TRUE(near(got->error_max, row.at("max"))) << got->error_max << " vs " << row.at("max");
  }
  // The four scenes at 1, 4, 8 and 16 samples at least.
  for (const char* scene : {"thin", "sliver", "near_horizontal", "near_vertical"}) {
    int seen = 0;
    for (const aa_test::TableRow& row : rows)
      if (row.at("scene") == scene && (row.at("samples") == "1" || row.at("samples") == "4" ||
                                       row.at("samples") == "8" || row.at("samples") == "16"))
        ++seen;
    EXPECT_EQ(seen, 4) << scene;
  }
}

}  // namespace
}  // namespace rastsim
