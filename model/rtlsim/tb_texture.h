// SPDX-License-Identifier: Apache-2.0
// The texel memory behind rast_top's texel fetch port in co-simulation (docs/texture.md
// "RTL"): each request's texels read from the placed textures (TbSetup::texels, the
// reference TextureUnit's placement), decoded to RGBA8, and its fetches made, in order,
// through the reference's texture cache model (ref/memory's SetAssocCache with
// texture.cache_bytes, ways, line_bytes: render's hits and misses where the RTL fetches
// in the reference's order).
//
// Timing: the port answers in request order, a response a cycle at most; a request taken
// at cycle t with m line misses (no cache: every texel a miss) is answered from cycle
//     due = s + stall,   s = max(t + 1, due_prev + 1)
// the blocking cache of the timed stage (docs/texture.md "Timed texture stage"): with
// memory.model = "fixed" stall = m texture.miss_cycles (TimingParams::texture_batch_cycles);
// with "dram" the misses are the fills of the memory system's client `texture`, one in
// flight, issued from s (timing/texture_memory_port.h: TextureMemoryPort, the SystemC
// stage's own rule), stall = the last fill's arrival - s. A request's fills are issued in
// cycle s itself (not when the request is taken), so the memory system sees the texture's
// and the ROP's requests in time order.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "ref/memory/cache.h"
#include "timing/texture_memory_port.h"
#include "rtlsim/testbench.h"

namespace rastsim::rtlsim {

class TbTexture {
 public:
  explicit TbTexture(const TbSetup& s);
  // memory.model = "dram": the fills through `mem` (the ROP's memory system).
  void attach(MemorySystem& mem) { mem_ = std::make_unique<TextureMemoryPort>(mem); }
  // Before the clock falls: the head response once due, the request port ready.
  void drive(uint64_t t, RastPorts& ports);
  // After the clock falls: the response taken, a request taken (its texels read, its
  // fetches made). A wrong request (count, format, an address not a texel's) sets
  // `error`.
  void serve(uint64_t t, RastPorts& ports, std::string& error);
  bool idle() const { return queue_.empty(); }
  void finish(CosimResult& r) const;

 private:
  struct Pending {
    uint64_t taken = 0;              // the cycle the request was taken
    bool issued = false;             // its fills made, `due` known
    uint64_t due = 0;
    std::array<uint32_t, 4> texels{};
    std::array<uint64_t, 4> fills{}; // the misses' DRAM reads: line (or texel) addresses
    int misses = 0;
  };
  // The requests whose s has come, in order: their fills made, their due set.
  void issue(uint64_t t);
  const TbSetup& s_;
  std::optional<SetAssocCache> cache_;
  std::unique_ptr<TextureMemoryPort> mem_;  // memory.model = "dram" (null: fixed)
  std::deque<Pending> queue_;
  uint64_t last_due_ = 0;
  bool offered_ = false;  // the head response offered this cycle
  uint64_t fetches_ = 0, hits_ = 0, misses_ = 0;
};

}  // namespace rastsim::rtlsim
