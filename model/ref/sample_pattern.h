// SPDX-License-Identifier: Apache-2.0
// Multisample positions (raster.samples, docs/antialiasing.md).
//
// - The standard Direct3D 11 / Vulkan sample positions for 1, 2, 4, 8 and 16 samples,
//   in 1/16 pixel from the pixel centre, x right and y down (the screen's axes). Sample
//   s of a pixel is its centre plus offset s; 1 sample is the centre itself.
// - Each offset is snapped to raster.coord_format's sub-pixel grid: raw = off * 2^F / 16,
//   exact for F >= 4, rounded to nearest (ties to even) below that, so two samples of a
//   coarse grid can fall on one point (the coverage test is still per sample).
// - Coverage of sample s by an edge E = a x + b y + c is E(centre) + a dx_s + b dy_s
//   (+ bias) >= 0: the top-left rule applies per sample, so shared edges stay
//   watertight sample by sample.
#pragma once

#include <array>
#include <cstdint>

namespace rastsim {

inline constexpr int kMaxSamples = 16;

// True for the sample counts raster.samples accepts: 1, 2, 4, 8, 16.
constexpr bool valid_sample_count(int n) { return n == 1 || n == 2 || n == 4 || n == 8 || n == 16; }

// The coverage mask of a pixel whose `samples` samples are all covered.
constexpr uint32_t full_sample_mask(int samples) { return samples >= 32 ? ~0u : (1u << samples) - 1; }

// The standard offsets of an n-sample pattern, in 1/16 pixel: {dx, dy} per sample.
// n must be a valid sample count.
const std::array<std::array<int, 2>, kMaxSamples>& standard_sample_offsets_16th(int n);

struct SamplePattern {
  int count = 1;
  std::array<int64_t, kMaxSamples> dx{}, dy{};  // raw s.I.F units from the pixel centre
  // The offsets' bounding box (raw): coarse raster tests a tile's extreme corners moved
  // by these, so early-out and early-in stay conservative over every sample.
  int64_t dx_min = 0, dx_max = 0, dy_min = 0, dy_max = 0;
  uint32_t full_mask() const { return full_sample_mask(count); }
};

// The snapped pattern of `samples` samples for `frac_bits` fraction bits (1..62);
// a reference into a table built once.
const SamplePattern& sample_pattern(int samples, int frac_bits);

}  // namespace rastsim
