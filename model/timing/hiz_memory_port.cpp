// SPDX-License-Identifier: Apache-2.0
#include "timing/hiz_memory_port.h"

#include <algorithm>

namespace rastsim {

void HizMemoryPort::attach(HizTable& table) {
  table_ = &table;
  table.on_access = [this](uint64_t address, uint64_t bytes, bool write) { access(address, bytes, write); };
}

void HizMemoryPort::access(uint64_t address, uint64_t bytes, bool write) {
  if (defer_) return;  // the flush: the engine makes it (sc/hiz_flush.h)
  if (write) {  // a flush not deferred (no engine): posted at the step's cycle
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
  // Only this test's reads are outstanding: the ROP (its flushes included) and the texture
  // stage wait for their own before their stages yield; the scan-out's are not waited for here.
  const uint64_t done = mem_.wait_reads().value_or(start_);
  const uint64_t stall = done > start_ ? done - start_ : 0;
  report_.stall_cycles += stall;
  return stall;
}

uint64_t HizMemoryPort::flush_read(int64_t block, uint64_t r) {
  const uint64_t bytes = uint64_t(table_->entry_bytes());
  mem_.issue_read(MemClient::Hiz, table_->entry_address(block), bytes, r);
  report_.bytes_read += bytes;
  ++report_.reads;
  // The engine's only read in flight; no other client's is outstanding (they wait for
  // their own before they yield).
  return std::max(r + 1, mem_.wait_reads().value_or(0));
}

void HizMemoryPort::write_back(int64_t block, uint64_t w) {
  const uint64_t bytes = uint64_t(table_->entry_bytes());
  mem_.post_write(MemClient::Hiz, table_->entry_address(block), bytes, w);
  report_.bytes_written += bytes;
  ++report_.writes;
}

void add_hiz_memory_json(nlohmann::json& j, const HizMemoryReport& r) {
  j["memory"]["clients"][kHizClient].update(
      {{"reads", r.reads}, {"writes", r.writes}, {"stall_cycles", r.stall_cycles}});
}

}  // namespace rastsim
