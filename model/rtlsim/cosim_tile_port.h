// SPDX-License-Identifier: Apache-2.0
// The port adapter's binned-mode ports (cosim_driver.h): rast_top's bin rectangle on the
// command port (cmd_bin_i) and the tile buffer's memory port (tl_*, rtl/rast_tile_buffer.sv),
// on a verilated rast_top of any config (PixelW, TilePortWords from RtlParams).
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include "rtlsim/port_bits.h"
#include "rtlsim/rtl_params.h"
#include "rtlsim/testbench.h"

namespace rastsim::rtlsim {

// cmd_bin_i = {y1, x1, y0, x0} (PixelW bits each) from bin = {x0, y0, x1, y1}; 0 without one.
template <class V>
void drive_bin_rect(V& top, const RtlParams& p, const int* bin) {
  for (int k = 0; k < 4; ++k) set_port_bits(top.cmd_bin_i, k * p.pixel_w, p.pixel_w, bin ? uint64_t(bin[k]) : 0);
}

template <class V>
TileBeat tile_beat_of(const V& top, const RtlParams& p) {
  TileBeat b;
  b.valid = top.tl_valid_o;
  b.write = top.tl_write_o;
  b.addr = top.tl_addr_o;
  b.count = int(top.tl_count_o);
  b.words.resize(size_t(p.tile_port_words));  // the store beat taken a cycle ago
  for (int i = 0; i < p.tile_port_words; ++i) b.words[size_t(i)] = uint32_t(port_bits(top.tl_wdata_o, i * 32, 32));
  return b;
}

template <class V>
void drive_tile_of(V& top, bool ready, bool rvalid, const std::vector<uint32_t>& words) {
  top.tl_ready_i = ready;
  top.tl_rvalid_i = rvalid;
  for (size_t i = 0; i < words.size(); ++i) set_port_word(top.tl_rdata_i, i, words[i]);
}

}  // namespace rastsim::rtlsim
