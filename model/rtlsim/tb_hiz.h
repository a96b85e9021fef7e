// SPDX-License-Identifier: Apache-2.0
// The memory behind rast_top's Hi-Z spilled-entry port in co-simulation (rtl/rast_hiz_spill.sv,
// hiz_mem_*; docs/depth-culling.md "Spilled table", "RTL"): client `hiz` of the memory system.
//
// - Function: the entries the RTL wrote, by byte address (a block never written back is
//   never read for its data: the RTL's fresh bits give the cleared entry); a read returns
//   the bytes as they are when the request is taken.
// - Checks: each request, in order within its kind, is the reference's (TbSetup's
//   hiz_test_reads, hiz_flush_reads, hiz_writes: HizTable::on_access's addresses); a
//   wrong address or an extra request is a mismatch, and so are fewer at the end, and
//   bytes unlike render's hiz_dram_bytes_read / _written.
// - Timing (memory.model = "dram"): a request taken at cycle t goes to the memory system
//   at t (timing/memory_system.h, client Hiz). A flush's read is the update engine's only
//   read in flight: its response comes at max(t + 1, c), c its completion. A test's reads
//   come one a cycle and are waited for together (the SystemC rule,
//   timing/hiz_memory_port.h: stall = max_k c_k - t0): once the RTL stops issuing them,
//   the last arrives at max(its t + 1, c_last), each earlier one a cycle before the next
//   at most. Write-backs are posted. "fixed": every response the next cycle (the SystemC
//   model has no memory for them: no stall).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <unordered_map>

#include "rtlsim/testbench.h"
#include "timing/hiz_memory_port.h"
#include "timing/memory_system.h"

namespace rastsim::rtlsim {

class TbHiz {
 public:
  explicit TbHiz(const TbSetup& s) : s_(s) {}
  void attach(MemorySystem& mem) { mem_ = &mem; }
  // Before the clock falls: the response due now, if any.
  void drive(uint64_t t, RastPorts& ports);
  // After the clock falls: the response taken, the request taken (checked; a wrong one
  // sets `error`).
  void serve(uint64_t t, RastPorts& ports, std::string& error);
  bool idle() const { return rsp_.empty(); }
  // The counts into `r` (memory.clients.hiz); fewer requests or other bytes than the
  // reference's set `error`.
  void finish(CosimResult& r, std::string& error) const;

 private:
  struct Response {
    uint64_t taken = 0, due = 0;  // the request's cycle; the response's (0: a test read not yet waited for)
    std::array<uint8_t, 64> data{};
  };
  void resolve_tests(uint64_t t);
  const TbSetup& s_;
  MemorySystem* mem_ = nullptr;  // memory.model = "dram" (null: fixed)
  std::unordered_map<uint64_t, std::array<uint8_t, 64>> entries_;
  std::deque<Response> rsp_;
  size_t unresolved_ = 0;  // test reads at rsp_'s back not yet waited for
  bool offered_ = false;
  size_t tests_ = 0, flushes_ = 0, writes_ = 0;  // requests taken of each kind
  HizMemoryReport report_;
};

}  // namespace rastsim::rtlsim
