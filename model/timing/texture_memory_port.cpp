// SPDX-License-Identifier: Apache-2.0
#include "timing/texture_memory_port.h"

#include <algorithm>

namespace rastsim {

void TextureMemoryPort::begin(uint64_t cycle) {
  start_ = cycle;
  stall_ = splits_ = 0;
}

uint64_t TextureMemoryPort::fill_at(uint64_t address, uint64_t bytes, uint64_t issue) {
  mem_.issue_read(MemClient::Texture, address, bytes, issue);
  // The only read outstanding: the ROP waits for its own fills before its stage yields
  // (RopMemoryPort::end), the scan-out's are not waited for here.
  const uint64_t done = mem_.wait_reads().value_or(issue);
  const uint64_t wait = done > issue ? done - issue : 0;
  report_.max_fill_cycles = std::max(report_.max_fill_cycles, wait);
  report_.stall_cycles += wait;
  report_.bytes_read += bytes;
  ++report_.reads;
  return wait;
}

void TextureMemoryPort::fill(uint64_t address, uint64_t bytes, uint64_t slot, bool split) {
  splits_ += split ? 1 : 0;
  const uint64_t wait = fill_at(address, bytes, start_ + slot + stall_ + splits_ + 1);
  stall_ += wait + kFillOverheadCycles;
  report_.stall_cycles += kFillOverheadCycles;
}

void add_texture_memory_json(nlohmann::json& j, const TextureMemoryReport& r) {
  j["memory"]["clients"][kTextureClient].update({{"bytes_read", r.bytes_read},
                                                 {"reads", r.reads},
                                                 {"stall_cycles", r.stall_cycles},
                                                 {"max_fill_cycles", r.max_fill_cycles}});
}

}  // namespace rastsim
