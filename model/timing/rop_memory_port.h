// SPDX-License-Identifier: Apache-2.0
// The ROP's memory clients (rop_color, rop_depth) on the timed memory system
// (timing/memory_system.h; docs/memory.md, "Timed memory system"): it runs the
// reference's functional memory system (ref/memory/rop_memory.h) on the ROP's own access
// stream (and the 2D engine's, which owns the ROP's port while it draws), so hits, misses
// and bytes equal render's, and issues each DRAM transfer the functional model reports
// (SurfaceClient::on_transfer) at its own address and size: a write-back at the evicted
// line, a fill at the missed line, each flushed line at the frame end. The SystemC ROP
// (sc/rop.h) and the RTL testbench (model/rtlsim) drive the same class.
//
// Order: a client's transfers wait until its next access (or the transaction's end):
// the requests of one cycle enter the DRAM in access order, a surface at a time, the
// colour surface's first at the transaction's end.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "ref/framebuffer.h"
#include "ref/memory/rop_memory.h"
#include "timing/memory_system.h"

namespace rastsim {

class RopMemoryPort {
 public:
  RopMemoryPort(MemorySystem& mem, const MemoryParams& p, const Framebuffer& fb, int depth_bits);
  RopMemoryPort(const RopMemoryPort&) = delete;
  RopMemoryPort& operator=(const RopMemoryPort&) = delete;

  // The functional model the ROP calls (ref/rop.h's mem argument).
  RopMemory& functional() { return rop_; }
  // Accesses from now on are made at core cycle `cycle` (the transaction's start).
  void begin(uint64_t cycle);
  // The transaction's accesses are all made: their requests issued, then its fills
  // waited for; returns the last fill's completion (nullopt: no fill).
  std::optional<uint64_t> end();
  // end(), then the transaction's cycles by timing/memory_timing.h's rule: `work_cycles`
  // or until its last fill has arrived plus one cycle, from its start `start`.
  uint64_t transaction_cycles(uint64_t work_cycles, uint64_t start);
  // After functional().clear_color() / clear_depth(): the clear's bytes written.
  void cleared(MemClient c);
  // The frame end (RopMemory::finish: resolve reads, flush, resolved image), made at
  // the current cycle; then the stats.
  void finish();
  MemoryStats stats() const { return rop_.stats(); }

 private:
  struct Surface {
    MemClient client;
    std::vector<MemoryTransfer> pending;  // reported, not yet issued
  };
  void settle(Surface& s);

  MemorySystem& mem_;
  RopMemory rop_;
  std::array<Surface, 2> surfaces_;
  uint64_t cycle_ = 0;
};

}  // namespace rastsim
