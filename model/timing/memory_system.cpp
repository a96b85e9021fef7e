// SPDX-License-Identifier: Apache-2.0
#include "timing/memory_system.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "timing/dram_trace.h"

namespace rastsim {

void MemorySystem::enqueue(MemClient c, uint64_t address, uint64_t bytes, bool write, uint64_t cycle) {
  // Every other client's requests of earlier cycles first (set_arrival_wait).
  if (arrival_wait_ && c != MemClient::Scanout) arrival_wait_(cycle, c);
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

// The DRAM's events before the self-timed client's next request s (at or before
// `limit`) in one call, up to the first that completes a request: until a completion
// nothing the callers' loops test changes (outstanding reads, the client's next
// request), so this is the same as one event a step. Then the client's request at s.
bool MemorySystem::step(uint64_t limit) {
  const uint64_t s = timed_ ? timed_->next_request_cycle() : SelfTimedClient::kNoRequest;
  constexpr uint64_t kNone = SelfTimedClient::kNoRequest;
  if (s > 0) {  // the DRAM's events strictly before s (the client goes first at equal cycles)
    const uint64_t e = dram_.advance_events(s == kNone ? limit : std::min(limit, s - 1));
    if (e != DramModel::kNoEvent) {
      floor_ = std::max(floor_, e);
      if (dram_.has_completions()) take_completions();
      return true;
    }
  }
  if (s == kNone || s > limit) return false;
  timed_->request(std::max(s, floor_));
  return true;
}

std::optional<uint64_t> MemorySystem::wait_reads() {
  while (outstanding_reads_ > 0)
    if (!step(DramModel::kNoEvent))
      throw std::logic_error("memory: " + std::to_string(outstanding_reads_) + " reads outstanding but the DRAM is idle");
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

}  // namespace rastsim
