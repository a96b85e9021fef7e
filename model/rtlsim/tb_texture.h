// SPDX-License-Identifier: Apache-2.0
// The memory behind rast_top's texture cache in co-simulation (docs/texture.md "RTL"):
// rast_texture_cache (inside rast_top) looks the texels up and asks this testbench only
// for line fills on tex_mem_*; each fill's bytes come from the placed textures
// (TbSetup::texture_memory: the reference TextureUnit's placement, each texel stored by
// encode_texel; bytes no texel holds are 0), in TexLineBytes / TexBeatBytes beats.
//
// Checks: the RTL's fills, in order, are the reference's (TbSetup::texture_fills, its
// texture cache's misses in fetch order: a wrong line address or an extra fill is a
// mismatch); its hits and misses (tex_hits_o, tex_miss_o) are counted and, at the end,
// its misses must equal the reference's.
//
// Timing: the fill port is ready while no fill is in flight (the cache keeps one); a fill
// taken at cycle t has its beats from cycle `first` on, one a cycle as the cache takes them:
// - memory.model = "fixed": first = t + 1 + max(0, texture.miss_cycles - 2 - Beats), so a
//   miss costs the cache 2 + Beats + that wait = texture.miss_cycles (at least 2 + Beats),
//   the SystemC stage's fixed rule;
// - "dram": the fill is a read of the memory system's client `texture` (the ROP's memory
//   system) made at t through the SystemC stage's own TextureMemoryPort, arriving at core
//   cycle c; the last beat comes in cycle max(t + Beats, c), the first Beats - 1 before it.
// A fill is issued in the cycle the cache's request is taken, before the ROP's requests of
// that cycle: the memory system sees the texture's and the ROP's requests in time order.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "timing/texture_memory_port.h"
#include "rtlsim/testbench.h"

namespace rastsim::rtlsim {

class TbTexture {
 public:
  explicit TbTexture(const TbSetup& s);
  // memory.model = "dram": the fills through `mem` (the ROP's memory system).
  void attach(MemorySystem& mem) { mem_ = std::make_unique<TextureMemoryPort>(mem); }
  // Before the clock falls: the fill port's ready, the next beat once due.
  void drive(uint64_t t, RastPorts& ports);
  // After the clock falls: the cache's hits and miss, a beat taken, a fill request taken
  // (checked against the reference's next fill: a wrong one sets `error`).
  void serve(uint64_t t, RastPorts& ports, std::string& error);
  bool idle() const { return !fill_; }
  // The counts into `r`; a miss count unlike the reference's sets `error`.
  void finish(CosimResult& r, std::string& error) const;

 private:
  struct Fill {
    uint64_t address = 0;  // the line's byte address
    uint64_t first = 0;    // the cycle its first beat is due
    int sent = 0;          // beats taken so far
  };
  const TbSetup& s_;
  std::unique_ptr<TextureMemoryPort> mem_;  // memory.model = "dram" (null: fixed)
  std::optional<Fill> fill_;
  bool ready_ = false, offered_ = false;  // this cycle: fill port ready, a beat offered
  int beats_ = 1;                         // beats a line: TexLineBytes / TexBeatBytes
  uint64_t fills_ = 0, hits_ = 0, misses_ = 0;
};

}  // namespace rastsim::rtlsim
