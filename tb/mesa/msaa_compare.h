// SPDX-License-Identifier: Apache-2.0
// 4x multisample coverage of the same triangles by the reference model and by llvmpipe,
// compared per (triangle, pixel): the number of covered samples, and the mask itself.
//
// - Reference, two ways that must agree: the whole pipeline (render_scene with
//   raster.samples = 4, msaa: one fragment a pixel carrying its sample mask) and the
//   model's per-pixel function pixel_sample_mask() evaluated directly over each set-up
//   triangle's bounding box widened by one pixel.
// - llvmpipe: OsMesaMsaa::sample_masks (one OR-ed bit per triangle, per sample).
// - Sample s is the same point in both (standard order; asserted by the tests), so the
//   masks are compared bit for bit as well as their popcounts.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "osmesa_msaa.h"
#include "ref/raster_state.h"

namespace rastsim::mesa {

using SampleMasks = std::array<std::vector<uint32_t>, kMsaaSamples>;  // [sample][pixel]: triangle bits

// The reference pipeline's fragments (st.samples must be 4): per sample, per pixel, bit i
// set when tris[i]'s fragment there covers that sample. Throws std::logic_error on a
// fragment that is not a triangle index, an empty mask, or a pixel emitted twice.
SampleMasks reference_sample_masks(const std::vector<GridTri>& tris, const RasterState& st);

// The same from setup_triangle() and pixel_sample_mask() over each triangle's bounding
// box widened by one pixel (clamped to the framebuffer). `on_edge`, if given, counts the
// covered-or-not samples lying exactly on an edge of the closed snapped triangle (the ones
// the fill rule decides).
SampleMasks direct_sample_masks(const std::vector<GridTri>& tris, const RasterState& st, uint64_t* on_edge);

// The 4-bit mask of triangle `bit` at pixel p.
inline uint32_t tri_mask(const SampleMasks& m, size_t p, int bit) {
  uint32_t r = 0;
  for (int s = 0; s < kMsaaSamples; ++s) r |= ((m[size_t(s)][p] >> bit) & 1u) << s;
  return r;
}

struct MsaaMismatch {
  size_t tri = 0;
  int x = 0, y = 0;
  uint32_t reference = 0, llvmpipe = 0;  // 4-bit sample masks
};

struct MsaaStats {
  uint64_t triangles = 0;
  uint64_t passes = 0;
  uint64_t decisions = 0;          // (triangle, pixel) pairs compared: triangles * fb pixels
  uint64_t sample_decisions = 0;   // (triangle, sample) pairs: 4 * decisions
  uint64_t pixels_covered = 0;     // pairs with at least one sample covered (reference)
  uint64_t pixels_partial = 0;     // pairs with 1..3 samples covered
  uint64_t samples_covered = 0;
  uint64_t samples_on_edge = 0;    // samples exactly on an edge of the closed triangle
  uint64_t count_mismatches = 0;   // pairs whose number of covered samples differs
  uint64_t mask_mismatches = 0;    // pairs whose masks differ (>= count_mismatches)
  uint64_t pipeline_vs_direct = 0; // pairs where the two reference answers differ
  MsaaStats& operator+=(const MsaaStats& o);
};

// Draws `tris` through both, 32 at a time; appends up to `max_report` mismatches.
MsaaStats compare_msaa(const std::vector<GridTri>& tris, const RasterState& st, OsMesaMsaa& gl,
                       std::vector<MsaaMismatch>& report, size_t max_report);

// "triangle #i (x0, y0) ...: pixel (x, y): rastsim samples 0101 (2), llvmpipe 0001 (1)",
// sample 0 first.
std::string describe(const MsaaMismatch& m, const std::vector<GridTri>& tris);

}  // namespace rastsim::mesa
