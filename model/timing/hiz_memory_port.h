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
// Reads are blocking, one in flight, from the tile's start t0: read k issued at i_k,
// arriving at c_k, i_1 = t0, i_{k+1} = c_k, and the walk stalls c_M - t0 cycles; the
// write-backs are posted at the cycle of the read before them. No spilled access: no stall.
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
  uint64_t stall_cycles = 0;  // sum over tiles of the rule's stall
};

class HizMemoryPort {
 public:
  explicit HizMemoryPort(MemorySystem& mem) : mem_(mem) {}
  HizMemoryPort(const HizMemoryPort&) = delete;
  HizMemoryPort& operator=(const HizMemoryPort&) = delete;

  // The table's spilled accesses go through this port from now on (sets
  // HizTable::on_access); the port must outlive the table's use.
  void attach(HizTable& table);
  // A tile starts at core cycle `cycle`: its stall restarts from 0.
  void begin(uint64_t cycle) { start_ = cycle_ = cycle; }
  // The stall since begin(): c_M - t0 (0 without a read).
  uint64_t stall_cycles() const { return cycle_ - start_; }
  const HizMemoryReport& report() const { return report_; }

 private:
  void access(uint64_t address, uint64_t bytes, bool write);
  MemorySystem& mem_;
  uint64_t start_ = 0, cycle_ = 0;
  HizMemoryReport report_;
};

// memory.clients.hiz.{reads, writes, stall_cycles} beside the functional counts.
void add_hiz_memory_json(nlohmann::json& j, const HizMemoryReport& r);

}  // namespace rastsim
