// SPDX-License-Identifier: Apache-2.0
#include "timing/rop_memory_port.h"

#include "timing/memory_timing.h"

namespace rastsim {

RopMemoryPort::RopMemoryPort(MemorySystem& mem, const MemoryParams& p, const Framebuffer& fb, int depth_bits)
    : mem_(mem), rop_(p, fb, depth_bits) {
  SurfaceClient* clients[2] = {&rop_.color, &rop_.depth};
  for (size_t k = 0; k < surfaces_.size(); ++k) {
    Surface& s = surfaces_[k];
    s.client = MemClient(k);
    clients[k]->on_access_after_transfer = [this, &s] { settle(s); };
    clients[k]->on_transfer = [&s](const MemoryTransfer& t) { s.pending.push_back(t); };
  }
}

// The surface's transfers reported so far, in order, as DRAM requests at the current cycle.
void RopMemoryPort::settle(Surface& s) {
  for (const MemoryTransfer& t : s.pending) {
    if (t.write) mem_.post_write(s.client, t.address, t.bytes, cycle_);
    else mem_.issue_read(s.client, t.address, t.bytes, cycle_);
  }
  s.pending.clear();
}

void RopMemoryPort::begin(uint64_t cycle) { cycle_ = cycle; }

std::optional<uint64_t> RopMemoryPort::end() {
  for (Surface& s : surfaces_) settle(s);
  return mem_.wait_reads();
}

uint64_t RopMemoryPort::transaction_cycles(uint64_t work_cycles, uint64_t start) {
  const std::optional<uint64_t> fill = end();
  return memory_transaction_cycles(work_cycles, start, fill.has_value(), fill.value_or(0));
}

void RopMemoryPort::cleared(MemClient c) { settle(surfaces_[size_t(c)]); }

void RopMemoryPort::finish() {
  rop_.finish();  // the resolve's accesses, the flush's lines and the resolved image report their transfers
  for (Surface& s : surfaces_) settle(s);
}

}  // namespace rastsim
