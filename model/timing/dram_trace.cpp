// SPDX-License-Identifier: Apache-2.0
// DRAMsim3-format traces (dram_trace.h).
#include "timing/dram_trace.h"

#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace rastsim {

void write_dram_trace(std::ostream& out, const DramParams& p, const DramRequest& r, uint64_t clock) {
  const uint64_t bb = p.burst_bytes();
  const uint64_t bytes = r.bytes ? r.bytes : 1;
  for (uint64_t b = r.address / bb; b <= (r.address + bytes - 1) / bb; ++b) {
    std::ostringstream line;
    line << "0x" << std::hex << b * bb << std::dec << (r.write ? " WRITE " : " READ ") << clock << '\n';
    out << line.str();
  }
}

std::vector<DramTraceLine> read_dram_trace(std::istream& in, const std::string& name) {
  std::vector<DramTraceLine> lines;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    std::istringstream fields(text);
    std::string address, op, cycle, extra;
    if (!(fields >> address)) continue;  // blank line
    auto fail = [&](const std::string& why) {
      throw std::runtime_error(name + ":" + std::to_string(number) + ": " + why + " (expected \"0x<hex address> " +
                               "READ|WRITE <cycle>\"): " + text);
    };
    if (!(fields >> op >> cycle) || (fields >> extra)) fail("not three fields");
    DramTraceLine l;
    try {
      size_t used = 0;
      l.address = std::stoull(address, &used, 16);
      if (used != address.size()) fail("bad address");
      l.clock = std::stoull(cycle, &used, 10);
      if (used != cycle.size()) fail("bad cycle");
    } catch (const std::logic_error&) {
      fail("bad number");
    }
    if (op != "READ" && op != "read" && op != "WRITE" && op != "write") fail("operation is not READ or WRITE");
    l.write = op == "WRITE" || op == "write";
    if (!lines.empty() && l.clock < lines.back().clock) fail("cycle decreases");
    lines.push_back(l);
  }
  return lines;
}

}  // namespace rastsim
