// SPDX-License-Identifier: Apache-2.0
// The port adapter's early-Z ports (cosim_driver.h): rast_top's frag_culled_o and the
// early test's depth read (ez_rd_lanes_o, ez_rd_x_o, ez_rd_y_o, ez_rd_depth_i;
// rtl/rast_early_z.sv), on a verilated rast_top of any config (tied off without DepthEarly).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "rtlsim/cosim_hiz_port.h"  // cosim_tile_port.h, port_bits.h, testbench.h

namespace rastsim::rtlsim {

// The lanes whose stored depth the early test reads this cycle (bit j: lane j).
template <class V>
uint32_t early_read_lanes_of(const V& top) {
  return uint32_t(top.ez_rd_lanes_o);
}

// Lane j's pixel {x, y} (pixel_w bits each).
template <class V>
std::pair<int, int> early_read_pixel_of(const V& top, int j, int pixel_w) {
  return {int(port_bits(top.ez_rd_x_o, j * pixel_w, pixel_w)), int(port_bits(top.ez_rd_y_o, j * pixel_w, pixel_w))};
}

// Their samples' stored depth, DepthW bits each (lane j sample s at word j MaxSamples + s),
// then rast_top evaluated again: the early test answers in the same cycle.
template <class V>
void drive_early_depth_of(V& top, int depth_w, const std::vector<uint32_t>& words) {
  for (size_t i = 0; i < words.size(); ++i) set_port_bits(top.ez_rd_depth_i, int(i) * depth_w, depth_w, words[i]);
  top.eval();
}

}  // namespace rastsim::rtlsim
