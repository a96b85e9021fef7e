// SPDX-License-Identifier: Apache-2.0
// The coverage-error study (docs/exact-coverage.md, docs/results.md "Anti-aliasing:
// coverage error"): how far each multisample mask is from the exact area coverage.
//
// - Every triangle of the scene is set up as render_scene sets it up, once per sample
//   count, and traversed by raster.traversal, which gives each pixel's mask. Measured:
//   every triangle that setup does not cull for zero area, facing or range. A triangle
//   culled only because no sample position of its box lies in the clip rectangle (a
//   sliver between samples) is measured too, with every mask empty: that is a coverage
//   error of multisampling, not a culled primitive.
// - Pixels inside the clip rectangle (viewport, scissor) only. A pixel is an edge pixel
//   of a triangle when its exact coverage f is strictly between 0 and 1, or its mask
//   is partial (0 < popcount < S), or the two disagree; its error is |popcount / S - f|.
//   Triangles are measured one by one (overlaps do not mix).
// - Figures per sample count: edge pixels, mean, RMS and maximum error.
#pragma once

#include <cstdint>
#include <vector>

#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

struct CoverageErrorStats {
  int samples = 1;
  uint64_t triangles = 0;     // triangles measured (see above)
  uint64_t edge_pixels = 0;
  double error_sum = 0, error_sq_sum = 0, error_max = 0;
  double mean() const;
  double rms() const;
};

struct CoverageErrorResult {
  std::vector<CoverageErrorStats> per_samples;  // in the order of the sample counts asked
  uint64_t pixels_clipped = 0;  // pixels that needed the rational clip (all sample counts)
  double wall_seconds = 0;
};

// Measures `scene` with `arch` (its raster.samples ignored) at each sample count of
// `samples` (1, 2, 4, 8, 16). Throws std::invalid_argument for another count, or for a
// count above 1 with raster.traversal = scanline; SceneError as render_scene does.
CoverageErrorResult measure_coverage_error(const Scene& scene, const RasterState& arch, const std::vector<int>& samples);

}  // namespace rastsim
