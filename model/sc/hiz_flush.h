// SPDX-License-Identifier: Apache-2.0
// Hi-Z's flush in the timed model as rtl/rast_hiz_spill.sv's update engine makes it
// (memory.model = "dram" with spilled blocks; docs/depth-culling.md, "Spilled table", the
// flush equation): a process of its own beside the ROP, its requests through the hiz
// client (timing/hiz_memory_port.h) at their own cycles, so they meet the ROP's and the
// tests' in the DRAM in time order (SimContext::memory_time_order).
//
// - The ROP hands it a bundle at each group response p that decided a depth write to a
//   spilled block (its writes in lane order), and one at the batch's end (the tile's last
//   group; with its writes when that group made some).
// - The engine takes a bundle from cycle p + 1 and its writes one a cycle: a block the tile
//   has already read is applied in the cycle s, the next write at s + 1; else its entry is
//   read in r = s and applied in d = max(r + 1, c) (c the read's completion), the next
//   write at d + 1. At the batch's end the blocks read are written back one a cycle in
//   first-write order from the cycle after, and the engine is free two cycles after the
//   last write-back (the bundle's pop, then the empty FIFO: rast_hiz_spill's busy_o low).
// - Coarse raster's test of a footprint with a spilled block goes at the first cycle from
//   its own at which the engine is idle (idle_from): no bundle decided before it left,
//   the engine free.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include <systemc>

#include "ref/hiz.h"
#include "sc/sim_context.h"
#include "timing/hiz_memory_port.h"

namespace rastsim::sc {

class HizFlush : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(HizFlush);
  HizFlush(sc_core::sc_module_name name, SimContext& ctx, HizMemoryPort& port)
      : sc_module(name), ctx_(ctx), port_(port) {
    SC_THREAD(run);
  }

  // The ROP: writes w[0, n) of a tile decided at cycle p; `end`: the tile's last group.
  void bundle(uint64_t p, const HizSpillWrite* w, size_t n, bool end) {
    Bundle b{p, {}, end};
    for (size_t k = 0; k < n; ++k) b.blocks.push_back(w[k].block);
    q_.push_back(std::move(b));
    pushed_.notify(sc_core::SC_ZERO_TIME);
  }
  // After the run: the cycle the engine went idle after its last bundle (0: none). The
  // run ends no earlier (rast_top's idle_o waits for rast_hiz_spill's busy_o).
  uint64_t end() const { return free_; }
  // Coarse raster: the first cycle >= t at which the engine is idle. Waits (SystemC time)
  // until t, when every bundle decided before t has been handed over (the stages run at
  // or ahead of SystemC time), and for the engine to take them.
  uint64_t idle_from(uint64_t t) {
    for (;;) {
      wait_until(t);
      while (!q_.empty() && q_.front().p < t) sc_core::wait(done_);  // the front: the one under way
      // SystemC time may be past t (coarse raster blocked on its output): the engine's
      // state at t is its busy spans', not its latest.
      while (!busy_.empty() && busy_.front().second <= t) busy_.pop_front();  // t only grows
      uint64_t u = t;
      for (const auto& [from, to] : busy_)
        if (from <= u && u < to) u = to;  // in order: a later span may hold the new u
      if (u == t) return t;
      t = u;
    }
  }

 private:
  struct Bundle {
    uint64_t p = 0;
    std::vector<int32_t> blocks;
    bool end = false;
  };
  void wait_until(uint64_t t) {
    const uint64_t now = ctx_.to_cycles(sc_core::sc_time_stamp());
    if (t > now) sc_core::wait(double(t - now) * ctx_.cycle);
  }
  // Before a request at cycle s: SystemC time s, one delta after the processes it woke, so
  // coarse raster's test reads of cycle s enter first (rast_hiz_spill's port serves the
  // tests while they run, else the engine).
  void after_tests(uint64_t s) {
    wait_until(s);
    sc_core::wait(sc_core::SC_ZERO_TIME);
  }
  void run() {
    for (;;) {
      while (q_.empty()) sc_core::wait(pushed_);
      const Bundle& b = q_.front();
      uint64_t s = std::max(free_, b.p + 1);
      for (int32_t block : b.blocks) {
        if (std::find(slots_.begin(), slots_.end(), block) != slots_.end()) {
          ++s;  // applied in s
          continue;
        }
        slots_.push_back(block);
        after_tests(s);
        s = port_.flush_read(block, s) + 1;  // applied in d, the next write at d + 1
      }
      if (b.end) {
        for (int32_t block : slots_) {
          after_tests(s);
          port_.write_back(block, s++);
        }
        slots_.clear();
        ++s;  // the pop; busy_o low the cycle after
      }
      free_ = s;
      if (!busy_.empty() && b.p + 1 <= busy_.back().second) busy_.back().second = std::max(busy_.back().second, s);
      else busy_.emplace_back(b.p + 1, s);
      q_.pop_front();
      done_.notify(sc_core::SC_ZERO_TIME);
      // SystemC time follows the engine to its idle cycle, as the requests' arrival waits
      // took it to theirs (a lock-step run ends at the latest of the stages' and this).
      wait_until(free_);
    }
  }
  SimContext& ctx_;
  HizMemoryPort& port_;
  std::deque<Bundle> q_;
  std::vector<int32_t> slots_;  // the tile's blocks read, in first-write order
  uint64_t free_ = 0;           // the engine's next free cycle
  std::deque<std::pair<uint64_t, uint64_t>> busy_;  // [p + 1, free) of each bundle, merged, in order
  sc_core::sc_event pushed_, done_;
};

}  // namespace rastsim::sc
