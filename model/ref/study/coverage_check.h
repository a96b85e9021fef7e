// SPDX-License-Identifier: Apache-2.0
// Coverage check of an inexact traversal method (raster.traversal = scanline) against
// the exact edge-function coverage, triangle by triangle and over the whole scene.
//
// - pixels_wrong: per triangle, the pixels in the symmetric difference of the method's
//   set and the exact set (fine_raster_partial over the triangle's clipped bbox, the
//   same function tiled and bbox use), summed over the triangles.
// - Per pixel of the framebuffer, over every triangle of the scene: n_exact (triangles
//   covering it by the exact rule) and n_method (by the method).
//   cracks: pixels with n_exact >= 1 and n_method == 0 (a pixel the exact rule covers
//   and no triangle of the method does: a hole along a shared edge, or an eroded
//   outline pixel);
//   overlaps: pixels with n_method >= 2 and n_method > n_exact (double cover the exact
//   rule does not have).
// The exact methods need no check: their coverage is the exact one by construction and
// by test (tb/test_traversal.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "ref/tri_setup.h"

namespace rastsim {

struct CoverageErrors {
  bool measured = false;  // true when the method is inexact and the counts were taken
  uint64_t pixels_wrong = 0, cracks = 0, overlaps = 0;
};

class CoverageCheck {
 public:
  CoverageCheck(int fb_width, int fb_height);
  // The method's pixels (each inside t.bbox, in any order, no repeats) for triangle t.
  void add_triangle(const SetupTriangle& t, int frac_bits, const std::vector<std::pair<int, int>>& method_pixels,
                    CoverageErrors& e);
  // Counts cracks and overlaps of the triangles added so far into e.
  void finish(CoverageErrors& e) const;

 private:
  int w_;  // framebuffer width in pixels (row stride of the counts)
  // Per pixel: triangles covering it, 16 bits each (saturating; a scene puts fewer than
  // 65535 triangles on one pixel).
  std::vector<uint16_t> n_exact_, n_method_;
  std::vector<uint8_t> scratch_;  // one triangle's bbox: bit 0 exact, bit 1 method
};

}  // namespace rastsim
