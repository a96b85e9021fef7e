// SPDX-License-Identifier: Apache-2.0
#include "timing/texture_memory_port.h"

#include <algorithm>

namespace rastsim {

void TextureMemoryPort::attach(TextureUnit& unit) {
  unit.on_fill = [this](uint64_t address, uint64_t bytes) { fill(address, bytes); };
}

void TextureMemoryPort::begin(uint64_t cycle) { start_ = cycle_ = cycle; }

void TextureMemoryPort::fill(uint64_t address, uint64_t bytes) {
  mem_.issue_read(MemClient::Texture, address, bytes, cycle_);
  // The only read outstanding: the ROP waits for its own fills before its stage yields
  // (RopMemoryPort::end), the scan-out's are not waited for here.
  const uint64_t done = mem_.wait_reads().value_or(cycle_);
  const uint64_t wait = done > cycle_ ? done - cycle_ : 0;
  report_.max_fill_cycles = std::max(report_.max_fill_cycles, wait);
  report_.stall_cycles += wait;
  report_.bytes_read += bytes;
  ++report_.reads;
  cycle_ += wait;
}

void add_texture_memory_json(nlohmann::json& j, const TextureMemoryReport& r) {
  j["memory"]["clients"][kTextureClient].update({{"bytes_read", r.bytes_read},
                                                 {"reads", r.reads},
                                                 {"stall_cycles", r.stall_cycles},
                                                 {"max_fill_cycles", r.max_fill_cycles}});
}

}  // namespace rastsim
