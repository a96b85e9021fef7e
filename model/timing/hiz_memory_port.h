// SPDX-License-Identifier: Apache-2.0
// The spilled Hi-Z table's client of the timed memory system (memory.model = "dram";
// timing/memory_system.h; docs/depth-culling.md, "Spilled table"): every access the
// table makes to an entry past its on-chip part (ref/hiz.h, HizTable::on_access: the
// entry's address depth.hiz_base + (i - on-chip blocks) x entry bytes, its entry bytes,
// read or write) is one DRAM request of client `hiz` at that address and size, so its
// bytes equal render's hiz_dram_bytes_read and hiz_dram_bytes_written.
//
// Timing rule (coarse raster, sc/coarse_raster.h): a tile's test reads the entries of the
// spilled blocks its footprint overlaps and cannot decide before they arrive; a drawn
// tile's flush reads each spilled block it wrote and writes it back (read-modify-write).
// A step's reads (the test's, then the flush's) are issued together at its start t0 and
// the walk waits for the last: read k arriving at core cycle c_k,
//   stall(step) = max(0, max_k c_k - t0)     (0 when the step reads no spilled entry),
// the flush starting when the test's reads have arrived; the write-backs are posted at
// the flush's start.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>
#include "ref/hiz.h"
#include "timing/memory_system.h"

namespace rastsim {

// What the Hi-Z client did (memory.clients.hiz.{reads, writes, stall_cycles}).
struct HizMemoryReport {
  uint64_t bytes_read = 0, bytes_written = 0;
  uint64_t reads = 0, writes = 0;
  uint64_t stall_cycles = 0;  // sum over steps of the rule's stall
};

class HizMemoryPort {
 public:
  explicit HizMemoryPort(MemorySystem& mem) : mem_(mem) {}
  HizMemoryPort(const HizMemoryPort&) = delete;
  HizMemoryPort& operator=(const HizMemoryPort&) = delete;

  // The table's spilled accesses go through this port from now on (sets
  // HizTable::on_access); the port must outlive the table's use.
  void attach(HizTable& table);
  // A step (a tile's test or its flush) starts at core cycle `cycle`.
  void begin(uint64_t cycle) { start_ = cycle; }
  // Waits for the step's reads: its stall, max_k c_k - t0 (0 without a read).
  uint64_t wait();
  const HizMemoryReport& report() const { return report_; }

 private:
  void access(uint64_t address, uint64_t bytes, bool write);
  MemorySystem& mem_;
  uint64_t start_ = 0;     // the step's t0
  uint64_t pending_ = 0;   // its reads issued, not yet waited for
  HizMemoryReport report_;
};

// memory.clients.hiz.{reads, writes, stall_cycles} beside the functional counts.
void add_hiz_memory_json(nlohmann::json& j, const HizMemoryReport& r);

}  // namespace rastsim
