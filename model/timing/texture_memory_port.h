// SPDX-License-Identifier: Apache-2.0
// The texture cache's client of the timed memory system (memory.model = "dram";
// timing/memory_system.h; docs/texture.md, "Timed texture stage"): every line fill the
// reference texture unit's cache makes (ref/texture/texture_unit.h, TextureUnit::on_fill:
// the missed line's address and line_bytes, or without a cache the texel's own address
// and bytes) is one DRAM read of client `texture`, at that address and size, so its
// bytes and reads equal render's texture_dram_bytes and texture_cache_misses.
//
// Timing rule (blocking, one miss in flight, as rtl/rast_texture_cache.sv in rast_top): a
// batch starting at core cycle t0 makes one texel request (a level sample) a cycle; the
// fill of a miss in request j (the j-th sample slot of the batch) is made when the cache
// looks the missing texel up, L_k, and requested the cycle after, i_k = L_k + 1:
//   L_k = t0 + j_k + S_{k-1} + (splits so far),  i_k = L_k + 1,
//   S_k = S_{k-1} + (c_k - i_k) + kFillOverheadCycles      (S_0 = 0, stall = S_M)
// c_k its line's arrival (MemorySystem::wait_reads), kFillOverheadCycles the cache's fill
// request cycle and the missing texel's second lookup after the line. A split (the missing
// texel not the first of its lookup group: TimingParams::TextureWork::miss_splits) delays
// the lookup a cycle; the batch counts it in its rate, not in the stall. The batch is busy
// texture_batch_cycles without misses plus the stall (the fixed rule's M x
// texture.miss_cycles with each miss's own DRAM latency, queueing included). An
// infinitely fast memory (c_k = i_k) costs kFillOverheadCycles a fill beyond the rate.
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
  uint64_t stall_cycles = 0;  // sum over batches of the rule's stall (the RTL's: its fills' waits)
  uint64_t max_fill_cycles = 0;  // the longest c_k - i_k
};

class TextureMemoryPort {
 public:
  explicit TextureMemoryPort(MemorySystem& mem) : mem_(mem) {}
  TextureMemoryPort(const TextureMemoryPort&) = delete;
  TextureMemoryPort& operator=(const TextureMemoryPort&) = delete;

  // The cache's own cycles a fill adds to its DRAM time (the rule above).
  static constexpr uint64_t kFillOverheadCycles = 2;
  // A batch starts at core cycle `cycle`: its stall restarts from 0.
  void begin(uint64_t cycle);
  // One fill, blocking (the rule above): its miss in the batch's sample slot `slot`,
  // `split` where it is not the first texel of its lookup group.
  void fill(uint64_t address, uint64_t bytes, uint64_t slot, bool split);
  // One fill made at core cycle `issue`, blocking; returns its wait c - issue (the RTL
  // testbench's fills, model/rtlsim/tb_texture.h, whose cache makes its own cycles).
  uint64_t fill_at(uint64_t address, uint64_t bytes, uint64_t issue);
  // The stall of the batch since begin(): S_M (0 without a fill).
  uint64_t stall_cycles() const { return stall_; }
  const TextureMemoryReport& report() const { return report_; }

 private:
  MemorySystem& mem_;
  uint64_t start_ = 0, stall_ = 0, splits_ = 0;  // the batch's t0, its stall and splits so far
  TextureMemoryReport report_;
};

// memory.clients.texture.{bytes_read, reads, stall_cycles, max_fill_cycles}.
void add_texture_memory_json(nlohmann::json& j, const TextureMemoryReport& r);

}  // namespace rastsim
