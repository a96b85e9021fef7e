// SPDX-License-Identifier: Apache-2.0
// The cost rules of a memory client's work with the timed memory system on
// (memory.model = "dram"; docs/memory.md, "Timed memory system"). Write-backs and clears'
// writes are posted everywhere: they occupy DRAM, the client does not wait for them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>

namespace rastsim {

// A transaction (the multisample resolve pass, a 2D operation, a scan-out line fetch)
// issues its line fills when it starts and cannot end before the last of them has
// arrived and been used, one cycle later: the cycles of a transaction starting at core
// cycle `start` whose own work takes `work_cycles`, when its last fill completed at core
// cycle `last_fill` (no fill: `has_fill` false, the work alone).
inline uint64_t memory_transaction_cycles(uint64_t work_cycles, uint64_t start, bool has_fill, uint64_t last_fill) {
  if (!has_fill) return work_cycles;
  const uint64_t fill_wait = last_fill + 1 > start ? last_fill + 1 - start : 0;
  return std::max(work_cycles, fill_wait);
}

// The ROP's fragment batches: one group in flight, as rtl/rast_rop.sv. A batch of A
// accesses (TimingParams::rop_accesses) is ceil(A / rop.pixels_per_cycle) groups of up to
// rop.pixels_per_cycle accesses in order, the last one short. Every memory access of a
// fragment (ref/rop.h rop_write: its samples' depth reads and writes and colour writes)
// is made by the group holding its first access. A group's read goes out at core cycle
// `issue` with the line fills its accesses miss; its response (depth test, write, and
// the next group's read) comes in the cycle
//   max(issue + 1, last fill's completion + 1)
// (issue + 1 with no fill: the fixed cost, a group a cycle). The batch lasts from its
// first group's issue to its last group's response. `last_fill`: the completion of the
// group's last fill (RopMemoryPort::end), nullopt when it has none.
inline uint64_t memory_group_response(uint64_t issue, std::optional<uint64_t> last_fill) {
  return std::max(issue + 1, last_fill ? *last_fill + 1 : 0);
}

}  // namespace rastsim
