// SPDX-License-Identifier: Apache-2.0
// The DRAM request stream in DRAMsim3's trace format (its TraceBasedCPU reads it; DRAMSys
// and Ramulator read the same three columns): one burst a line,
//   0x<address hex> READ|WRITE <cycle>
// the cycle in DRAM clocks (the memory controller's clock, as DRAMsim3 counts), lines in
// non-decreasing cycle order. `--mem-trace FILE` writes it; `rastsim dram-replay` reads it.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "timing/dram.h"

namespace rastsim {

struct DramTraceLine {
  uint64_t address = 0;  // bytes
  bool write = false;
  uint64_t clock = 0;    // DRAM clock of arrival
};

// One line a burst of `request` (the bursts of p.burst_bytes() it touches), arriving at
// DRAM clock `clock`.
void write_dram_trace(std::ostream& out, const DramParams& p, const DramRequest& request, uint64_t clock);

// Every line of a trace; `name` names the stream in errors ("name:line: ..."). Accepts
// what DRAMsim3 accepts: hex addresses with or without 0x, READ/read/WRITE/write, blank
// lines; throws std::runtime_error naming the line otherwise, or when cycles decrease.
std::vector<DramTraceLine> read_dram_trace(std::istream& in, const std::string& name);

}  // namespace rastsim
