// SPDX-License-Identifier: Apache-2.0
#include "ref/raster_state.h"

#include <algorithm>

namespace rastsim {

PixelRect PixelRect::intersect(const PixelRect& o) const {
  return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
}

PixelRect RasterState::clip_rect() const {
  PixelRect r{0, 0, std::min(viewport_width, fb_width), std::min(viewport_height, fb_height)};
  if (scissor_enabled) r = r.intersect(scissor);
  return r;
}

const char* to_string(DepthFunc f) {
  switch (f) {
    case DepthFunc::Never: return "never";
    case DepthFunc::Less: return "less";
    case DepthFunc::LEqual: return "lequal";
    case DepthFunc::Equal: return "equal";
    case DepthFunc::Greater: return "greater";
    case DepthFunc::GEqual: return "gequal";
    case DepthFunc::NotEqual: return "notequal";
    case DepthFunc::Always: return "always";
  }
  return "?";
}

}  // namespace rastsim
