// SPDX-License-Identifier: Apache-2.0
#include "ref/study/coverage_check.h"

#include "ref/fine_raster.h"

namespace rastsim {

CoverageCheck::CoverageCheck(int fb_width, int fb_height)
    : w_(fb_width), n_exact_(size_t(fb_width) * fb_height), n_method_(size_t(fb_width) * fb_height) {}

void CoverageCheck::add_triangle(const SetupTriangle& t, int frac_bits,
                                 const std::vector<std::pair<int, int>>& method_pixels, CoverageErrors& e) {
  e.measured = true;
  const PixelRect& bb = t.bbox;
  const int bw = bb.x1 - bb.x0;
  scratch_.assign(size_t(bb.area()), 0);
  auto bump = [](uint16_t& n) { n = uint16_t(n + (n != 0xffff)); };
  fine_raster_partial(t, bb, frac_bits, [&](int px, int py) {
    scratch_[size_t(py - bb.y0) * bw + (px - bb.x0)] |= 1;
    bump(n_exact_[size_t(py) * w_ + px]);
  });
  for (const auto& [px, py] : method_pixels) {
    scratch_[size_t(py - bb.y0) * bw + (px - bb.x0)] |= 2;
    bump(n_method_[size_t(py) * w_ + px]);
  }
  for (uint8_t s : scratch_) e.pixels_wrong += (s == 1 || s == 2);
}

void CoverageCheck::finish(CoverageErrors& e) const {
  for (size_t i = 0; i < n_exact_.size(); ++i) {
    e.cracks += n_exact_[i] >= 1 && n_method_[i] == 0;
    e.overlaps += n_method_[i] >= 2 && n_method_[i] > n_exact_[i];
  }
}

}  // namespace rastsim
