// SPDX-License-Identifier: Apache-2.0
#include "timing/hiz_memory_port.h"

namespace rastsim {

void HizMemoryPort::attach(HizTable& table) {
  table.on_access = [this](uint64_t address, uint64_t bytes, bool write) { access(address, bytes, write); };
}

void HizMemoryPort::access(uint64_t address, uint64_t bytes, bool write) {
  if (write) {  // the write-back: posted
    mem_.post_write(MemClient::Hiz, address, bytes, start_);
    report_.bytes_written += bytes;
    ++report_.writes;
    return;
  }
  mem_.issue_read(MemClient::Hiz, address, bytes, start_);
  report_.bytes_read += bytes;
  ++report_.reads;
  ++pending_;
}

uint64_t HizMemoryPort::wait() {
  if (pending_ == 0) return 0;
  pending_ = 0;
  // Only this step's reads are outstanding: the ROP and the texture stage wait for their
  // own before their stages yield; the scan-out's are not waited for here.
  const uint64_t done = mem_.wait_reads().value_or(start_);
  const uint64_t stall = done > start_ ? done - start_ : 0;
  report_.stall_cycles += stall;
  return stall;
}

void add_hiz_memory_json(nlohmann::json& j, const HizMemoryReport& r) {
  j["memory"]["clients"][kHizClient].update(
      {{"reads", r.reads}, {"writes", r.writes}, {"stall_cycles", r.stall_cycles}});
}

}  // namespace rastsim
