// SPDX-License-Identifier: Apache-2.0
// A RasterState for the stability tests, built field by field (not from a config) so a
// test can pick any format and a viewport the config schema would not allow.
#pragma once

#include <string>

#include "ref/raster_state.h"

namespace rastsim::testing {

inline RasterState stability_state(const std::string& format, int viewport_w, int viewport_h) {
  RasterState st;
  st.coord_format = FixedFormat::parse(format);
  st.tile_size = 16;
  st.fill_rule = FillRule::TopLeft;
  st.cull = CullMode::None;
  st.depth_func = DepthFunc::Always;
  st.depth_bits = 24;
  st.depth_write = true;
  st.out_of_range = OutOfRange::Cull;
  st.fb_width = st.viewport_width = viewport_w;
  st.fb_height = st.viewport_height = viewport_h;
  return st;
}

}  // namespace rastsim::testing
