// SPDX-License-Identifier: Apache-2.0
// The port adapter's Hi-Z spilled-entry port (cosim_driver.h): rast_top's hiz_mem_*
// (rtl/rast_hiz_spill.sv) and dbg_hiz_error_o, on a verilated rast_top of any config.
#pragma once

#include <array>
#include <cstdint>

#include "rtlsim/cosim_tile_port.h"  // port_bits.h, testbench.h

namespace rastsim::rtlsim {

// The request offered this cycle (the entry's bytes when a write-back) and the error flag.
template <class V>
HizRequest hiz_request_of(const V& top) {
  HizRequest r;
  r.error = top.dbg_hiz_error_o;
  r.valid = top.hiz_mem_req_valid_o;
  if (!r.valid) return r;
  r.write = top.hiz_mem_req_write_o;
  r.flush = top.hiz_mem_req_flush_o;
  r.address = top.hiz_mem_req_addr_o;
  for (size_t i = 0; i < r.data.size(); ++i) r.data[i] = uint8_t(port_bits(top.hiz_mem_req_data_o, int(8 * i), 8));
  return r;
}

// A read's response (or none), with the port's static inputs: depth.hiz_base and the
// request ready (always: the testbench takes every request in its cycle).
template <class V>
void drive_hiz_of(V& top, uint64_t base, bool valid, const std::array<uint8_t, 64>& data) {
  top.hiz_base_i = base;
  top.hiz_mem_req_ready_i = 1;
  top.hiz_mem_rsp_valid_i = valid;
  set_port_bytes(top.hiz_mem_rsp_data_i, data);
}

}  // namespace rastsim::rtlsim
