// SPDX-License-Identifier: Apache-2.0
#include "sc/memory.h"

#include <algorithm>
#include <utility>

#include "ref/framebuffer.h"
#include "sc/model_error.h"
#include "timing/dram_trace.h"

namespace rastsim::sc {

MemorySystem::MemorySystem(sc_core::sc_module_name name, const DramParams& p) : sc_module(name), dram_(p) {}

void MemorySystem::enqueue(MemClient c, uint64_t address, uint64_t bytes, bool write, uint64_t cycle) {
  // No request arrives before the DRAM's own time: one that would (a client behind the
  // others) arrives when the DRAM can still decide on it.
  cycle = std::max(cycle, floor_);
  // The self-timed client's requests due by now enter first, after the completions that
  // set them (the DRAM is stepped only while the client may have one due).
  if (timed_ && c != MemClient::Scanout)
    while ((timed_->reads_in_flight() || timed_->next_request_cycle() <= cycle) && step(cycle)) {}
  cycle = std::max(cycle, floor_);
  floor_ = cycle;
  for (uint64_t done = 0; done < bytes;) {
    const uint64_t n = std::min(kMaxRequestBytes, bytes - done);
    // Tags: the request number, times two, plus 1 for a write (the completion says which).
    const DramRequest r{address + done, write, uint32_t(n), int(c), next_tag_++ * 2 + (write ? 1 : 0)};
    dram_.enqueue(r, cycle);
    if (trace_) write_dram_trace(*trace_, dram_.params(), r, dram_.to_dram(cycle));
    if (!write && c != MemClient::Scanout) ++outstanding_reads_;  // the ones wait_reads waits for
    done += n;
  }
}

void MemorySystem::post_write(MemClient c, uint64_t address, uint64_t bytes, uint64_t cycle) {
  enqueue(c, address, bytes, true, cycle);
}

void MemorySystem::issue_read(MemClient c, uint64_t address, uint64_t bytes, uint64_t cycle) {
  enqueue(c, address, bytes, false, cycle);
}

void MemorySystem::take_completions() {
  for (const DramCompletion& d : dram_.take_completions()) {
    last_completion_ = std::max(last_completion_, d.cycle);
    if (d.tag % 2 == 1) continue;  // a posted write
    if (d.client == int(MemClient::Scanout)) {
      timed_->completed(d.cycle);
      continue;
    }
    --outstanding_reads_;
    last_read_ = std::max(last_read_.value_or(0), d.cycle);
  }
}

bool MemorySystem::step(uint64_t limit) {
  const uint64_t s = timed_ ? timed_->next_request_cycle() : SelfTimedClient::kNoRequest;
  const uint64_t e = dram_.next_event();
  const uint64_t first = std::min(s, e);
  if (first == DramModel::kNoEvent || first > limit) return false;
  if (s <= e) {
    timed_->request(std::max(s, floor_));
    return true;
  }
  dram_.advance_to(e);
  floor_ = std::max(floor_, e);
  take_completions();
  return true;
}

std::optional<uint64_t> MemorySystem::wait_reads() {
  while (outstanding_reads_ > 0)
    if (!step(DramModel::kNoEvent))
      throw ModelError("memory: " + std::to_string(outstanding_reads_) + " reads outstanding but the DRAM is idle");
  return std::exchange(last_read_, std::nullopt);
}

uint64_t MemorySystem::drain() {
  while (step(DramModel::kNoEvent)) {}
  return last_completion_;
}

MemorySystemReport MemorySystem::report(uint64_t run_cycles) const {
  MemorySystemReport r;
  r.dram = dram_.stats();
  r.preset = dram_.params().preset;
  r.dram_end_cycle = last_completion_;
  r.elapsed_cycles = std::max(run_cycles, last_completion_);
  r.bandwidth_utilisation = dram_.bandwidth_utilisation(r.dram.total().data_bus_clocks, r.elapsed_cycles);
  r.peak_bytes_per_kcycle =
      uint64_t(dram_.params().peak_bytes_per_second() / (double(dram_.params().core_khz) * 1e3) * 1000.0);
  return r;
}

RopMemoryPort::RopMemoryPort(MemorySystem& mem, const MemoryParams& p, const Framebuffer& fb, int depth_bits)
    : mem_(mem), rop_(p, fb, depth_bits) {
  const CacheParams caches[2] = {p.color_cache, depth_cache_params(p, fb.samples, depth_bits)};
  SurfaceClient* clients[2] = {&rop_.color, &rop_.depth};
  for (size_t k = 0; k < surfaces_.size(); ++k) {
    Surface& s = surfaces_[k];
    s.client = MemClient(k);
    s.functional = clients[k];
    if (caches[k].bytes > 0) s.tags.emplace(caches[k]);
    s.line_bytes = uint64_t(caches[k].line_bytes);
    s.functional->on_access = [this, &s](uint64_t address, bool write) { on_access(s, address, write); };
  }
}

// The access before this one is complete in the functional model (its bytes counted):
// issue it, then note this one's fill and write-back addresses from the tag store.
void RopMemoryPort::on_access(Surface& s, uint64_t address, bool write) {
  settle(s);
  s.pending = true;
  s.fill_address = s.writeback_address = address;  // no cache: the sample itself
  if (!s.tags) return;
  const uint64_t base = s.functional->layout().base();
  const uint64_t line = (address - base) / s.line_bytes;
  SetAssocCache::Victim victim;
  s.tags->access(line, write, victim);
  s.fill_address = base + line * s.line_bytes;
  if (victim.dirty) s.writeback_address = base + victim.line * s.line_bytes;
}

// The last access's bytes, as the functional model counted them: its write-back (and any
// fast-cleared block it materialised, written from the same address) before its fill.
void RopMemoryPort::settle(Surface& s) {
  if (!s.pending) return;
  s.pending = false;
  const MemoryClientStats& st = s.functional->stats();
  if (st.bytes_written > s.written_seen)
    mem_.post_write(s.client, s.writeback_address, st.bytes_written - s.written_seen, cycle_);
  if (st.bytes_read > s.read_seen) mem_.issue_read(s.client, s.fill_address, st.bytes_read - s.read_seen, cycle_);
  s.read_seen = st.bytes_read;
  s.written_seen = st.bytes_written;
}

void RopMemoryPort::begin(uint64_t cycle) { cycle_ = cycle; }

std::optional<uint64_t> RopMemoryPort::end() {
  for (Surface& s : surfaces_) settle(s);
  return mem_.wait_reads();
}

void RopMemoryPort::cleared(MemClient c) {
  Surface& s = surfaces_[size_t(c)];
  settle(s);
  if (s.tags) s.tags->invalidate_all();
  const uint64_t written = s.functional->stats().bytes_written;
  if (written > s.written_seen) mem_.post_write(s.client, s.functional->layout().base(), written - s.written_seen, cycle_);
  s.written_seen = written;
}

// The frame end's bytes after the last access: the resolve's last fill, then the
// written bytes spread evenly over the flushed lines in flush order (the functional
// model counts the flush as one total; plane-compressed blocks and the resolved image
// make line sizes differ, so the addresses are the lines', the sizes the even share).
void RopMemoryPort::settle_flush(Surface& s, const std::vector<uint64_t>& lines) {
  const MemoryClientStats& st = s.functional->stats();
  if (s.pending && st.bytes_read > s.read_seen)
    mem_.issue_read(s.client, s.fill_address, st.bytes_read - s.read_seen, cycle_);
  std::vector<uint64_t> targets;
  if (s.pending && s.writeback_address != s.fill_address) targets.push_back(s.writeback_address);
  for (uint64_t line : lines) targets.push_back(s.functional->layout().base() + line * s.line_bytes);
  if (targets.empty()) targets.push_back(s.functional->layout().base());
  const uint64_t total = st.bytes_written - s.written_seen;
  for (size_t i = 0; i < targets.size(); ++i) {
    const uint64_t n = total * (i + 1) / targets.size() - total * i / targets.size();
    if (n > 0) mem_.post_write(s.client, targets[i], n, cycle_);
  }
  s.pending = false;
  s.read_seen = st.bytes_read;
  s.written_seen = st.bytes_written;
}

void RopMemoryPort::finish() {
  rop_.finish();  // the resolve's accesses pass through on_access
  for (Surface& s : surfaces_) {
    std::vector<uint64_t> lines;
    if (s.tags) s.tags->write_back_all([&](uint64_t line) { lines.push_back(line); });
    settle_flush(s, lines);
  }
}

void add_memory_system_json(nlohmann::json& j, const MemorySystemReport& r) {
  const DramClientStats t = r.dram.total();
  j["dram_row_hit_rate"] = t.row_hit_rate();
  j["dram_bandwidth_utilisation"] = r.bandwidth_utilisation;
  j["memory"]["dram"] = {{"preset", r.preset},
                         {"bytes_read", t.bytes_read},
                         {"bytes_written", t.bytes_written},
                         {"bursts_read", t.bursts_read},
                         {"bursts_written", t.bursts_written},
                         {"activates", r.dram.activates},
                         {"precharges", r.dram.precharges},
                         {"refreshes", r.dram.refreshes},
                         {"end_cycle", r.dram_end_cycle},
                         {"peak_bytes_per_kcycle", r.peak_bytes_per_kcycle}};
  for (size_t k = 0; k < r.dram.clients.size() && k < kMemClientNames.size(); ++k) {
    const DramClientStats& c = r.dram.clients[k];
    nlohmann::json& o = j["memory"]["clients"][kMemClientNames[k]];
    o["bursts_read"] = c.bursts_read;
    o["bursts_written"] = c.bursts_written;
    o["row_hits"] = c.row_hits;
    o["row_misses"] = c.row_misses;
    o["row_conflicts"] = c.row_conflicts;
    o["mean_read_latency_cycles"] = c.requests_read ? double(c.read_latency_cycles) / double(c.requests_read) : 0.0;
  }
}

}  // namespace rastsim::sc
