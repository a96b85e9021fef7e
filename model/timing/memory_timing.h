// SPDX-License-Identifier: Apache-2.0
// The cost rule of a memory client's transaction with the timed memory system on
// (memory.model = "dram"; docs/memory.md, "Timed memory system (SystemC)"): the
// transaction issues its line fills when it starts and cannot end before the last of
// them has arrived and been used, one cycle later. Its write-backs are posted (they
// occupy DRAM, the client does not wait for them).
#pragma once

#include <algorithm>
#include <cstdint>

namespace rastsim {

// Cycles of a transaction starting at core cycle `start` whose own work takes
// `work_cycles`, when its last fill completed at core cycle `last_fill` (no fill:
// `has_fill` false, the work alone).
inline uint64_t memory_transaction_cycles(uint64_t work_cycles, uint64_t start, bool has_fill, uint64_t last_fill) {
  if (!has_fill) return work_cycles;
  const uint64_t fill_wait = last_fill + 1 > start ? last_fill + 1 - start : 0;
  return std::max(work_cycles, fill_wait);
}

}  // namespace rastsim
