// SPDX-License-Identifier: Apache-2.0
// The texture cache's client of the timed memory system (memory.model = "dram";
// timing/memory_system.h; docs/texture.md, "Timed texture stage"): every line fill the
// reference texture unit's cache makes (ref/texture/texture_unit.h, TextureUnit::on_fill:
// the missed line's address and line_bytes, or without a cache the texel's own address
// and bytes) is one DRAM read of client `texture`, at that address and size, so its
// bytes and reads equal render's texture_dram_bytes and texture_cache_misses.
//
// Timing rule (blocking, one miss in flight): a batch's fills are made in fetch order
// from the batch's start t0; fill k is issued at i_k and waited for, its line arriving at
// core cycle c_k (MemorySystem::wait_reads), and the texture pipeline stalls until then:
//   i_1 = t0,  i_{k+1} = c_k,  stall = sum_k (c_k - i_k) = c_M - t0
// and the batch is busy texture_batch_cycles without misses plus that stall (the fixed
// rule's M x texture.miss_cycles with each miss's own DRAM latency, queueing included).
// An infinitely fast memory (c_k = i_k) costs nothing beyond the sample rate.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>
#include "ref/texture/texture_unit.h"
#include "timing/memory_system.h"

namespace rastsim {

// What the texture client did (memory.clients.texture.* beside the DRAM's per-client
// figures; docs/stats.md).
struct TextureMemoryReport {
  uint64_t bytes_read = 0;    // = texture_dram_bytes
  uint64_t reads = 0;         // line fills (= texture_cache_misses)
  uint64_t stall_cycles = 0;  // sum over batches of the rule's stall
  uint64_t max_fill_cycles = 0;  // the longest c_k - i_k
};

class TextureMemoryPort {
 public:
  explicit TextureMemoryPort(MemorySystem& mem) : mem_(mem) {}
  TextureMemoryPort(const TextureMemoryPort&) = delete;
  TextureMemoryPort& operator=(const TextureMemoryPort&) = delete;

  // The unit's fills go through this port from now on (sets TextureUnit::on_fill); the
  // port must outlive the unit's use.
  void attach(TextureUnit& unit);
  // A batch starts at core cycle `cycle`: its stall restarts from 0.
  void begin(uint64_t cycle);
  // One fill, blocking (the rule above).
  void fill(uint64_t address, uint64_t bytes);
  // The stall of the batch since begin(): c_M - t0 (0 without a fill).
  uint64_t stall_cycles() const { return cycle_ - start_; }
  const TextureMemoryReport& report() const { return report_; }

 private:
  MemorySystem& mem_;
  uint64_t start_ = 0, cycle_ = 0;  // the batch's t0; the next fill's issue cycle
  TextureMemoryReport report_;
};

// memory.clients.texture.{bytes_read, reads, stall_cycles, max_fill_cycles}.
void add_texture_memory_json(nlohmann::json& j, const TextureMemoryReport& r);

}  // namespace rastsim
