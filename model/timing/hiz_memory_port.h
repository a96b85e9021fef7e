// SPDX-License-Identifier: Apache-2.0
// The spilled Hi-Z table's client of the timed memory system (memory.model = "dram";
// timing/memory_system.h; docs/depth-culling.md, "Spilled table"): every access the
// table makes to an entry past its on-chip part (ref/hiz.h, HizTable::on_access: the
// entry's address depth.hiz_base + (i - on-chip blocks) x entry bytes, its entry bytes,
// read or write) is one DRAM request of client `hiz` at that address and size, so its
// bytes equal render's hiz_dram_bytes_read and hiz_dram_bytes_written.
//
// Timing rule (coarse raster, sc/coarse_raster.h): a tile's test reads the entries of the
// spilled blocks its footprint overlaps and cannot decide before they arrive. Its reads are
// issued together at the test's cycle t0 and the walk waits for the last: read k arriving
// at core cycle c_k,
//   stall(test) = max(0, max_k c_k - t0)     (0 when the test reads no spilled entry).
// The flush (a drawn tile's read-modify-write of each spilled block it wrote) is timed as
// rtl/rast_hiz_spill.sv's update engine makes it (sc/hiz_flush.h; docs/depth-culling.md,
// "Spilled table", the one equation both sides quote), off the walk: the ROP's depth
// writes to spilled blocks reach the engine a group at a time, the tile's first write to a
// block reads its entry, and the batch's end writes the entries back in first-write order;
// a test that reads spilled entries waits until the engine is idle.
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
  uint64_t stall_cycles = 0;  // sum over tests of the rule's stall (the walk's waits)
};

class HizMemoryPort {
 public:
  explicit HizMemoryPort(MemorySystem& mem) : mem_(mem) {}
  HizMemoryPort(const HizMemoryPort&) = delete;
  HizMemoryPort& operator=(const HizMemoryPort&) = delete;

  // The table's spilled accesses go through this port from now on (sets
  // HizTable::on_access); the port must outlive the table's use.
  void attach(HizTable& table);
  // A test starts at core cycle `cycle`: its reads are issued then.
  void begin(uint64_t cycle) { start_ = cycle; }
  // Waits for the test's reads: its stall, max_k c_k - t0 (0 without a read).
  uint64_t wait();
  // While on, the table's accesses are not issued (HizTracker::apply's flush, which
  // the engine, sc/hiz_flush.h, makes at its own cycles instead).
  void defer(bool on) { defer_ = on; }
  // The flush engine's requests (sc/hiz_flush.h, docs/depth-culling.md "Spilled
  // table"): block i's entry read issued at core cycle r, returning the cycle the engine
  // applies its write, max(r + 1, c) with c the read's completion; its write-back posted
  // at cycle w.
  uint64_t flush_read(int64_t block, uint64_t r);
  void write_back(int64_t block, uint64_t w);
  const HizMemoryReport& report() const { return report_; }

 private:
  void access(uint64_t address, uint64_t bytes, bool write);
  MemorySystem& mem_;
  const HizTable* table_ = nullptr;
  uint64_t start_ = 0;     // the test's t0
  uint64_t pending_ = 0;   // its reads issued, not yet waited for
  bool defer_ = false;
  HizMemoryReport report_;
};

// memory.clients.hiz.{reads, writes, stall_cycles} beside the functional counts.
void add_hiz_memory_json(nlohmann::json& j, const HizMemoryReport& r);

}  // namespace rastsim
