// SPDX-License-Identifier: Apache-2.0
// The timed memory system (memory.model = "dram"; docs/memory.md, "Timed memory system"):
// one object every memory client goes through, wrapping the shared DRAM model
// (timing/dram.h) built from ArchParams::dram. Plain C++ (no SystemC): the SystemC model
// and the RTL testbench (model/rtlsim) run the same one, so their DRAM timing can agree.
//
// Time: the object works in its clients' own time (in the SystemC model, temporal
// decoupling like its Links, sc/link.h; in the RTL testbench, the cycle being clocked): a request carries the core cycle it is made at, and the DRAM model is
// advanced event by event (DramModel::next_event, never a cycle at a time) only as far
// as a client needs an answer. A blocking read (wait_reads) returns the core cycle the
// DRAM's completion arrives; posted writes occupy the DRAM and return nothing.
//
// Arbitration: requests enter the DRAM model in arrival-cycle order; requests of one
// cycle in the order they are made, which within a client is its access order and
// across clients scanout first (the display's deadline is hard), then rop_color,
// rop_depth. Inside the DRAM model FR-FCFS decides, with no client priority.
//
// The scan-out's line fetch (display/scanout_fetch.h: ScanoutFetch) is a self-timed client: it
// makes its requests of its own accord as display time passes, so the object runs it
// inside its event loop (step): before any other client's request enters at cycle c,
// every scan-out request due at or before c has entered, the DRAM first advanced to c
// while scan-out reads are in flight (their completions set its next request).
//
// The ROP's client, RopMemoryPort, is in timing/rop_memory_port.h.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "ref/hiz.h"
#include "ref/memory/bin_memory.h"
#include "ref/memory/rop_memory.h"
#include "timing/dram.h"

namespace rastsim {

// The clients: the index of each one's DRAM stats and its stats name
// (memory.clients.<name>).
// texture: the texture cache's line fills (timing/texture_memory_port.h); hiz: the spilled
// Hi-Z table's entries (timing/hiz_memory_port.h, at depth.hiz_base); binning and
// tile_store: pipeline.mode = binned's parameter buffer and bin loads/stores (sc/binning.h,
// ref/memory/bin_memory.h).
enum class MemClient { RopColor = 0, RopDepth = 1, Scanout = 2, Texture = 3, Hiz = 4, Binning = 5, TileStore = 6 };
inline constexpr const char* kScanoutClient = "scanout";
inline constexpr const char* kTextureClient = "texture";
inline constexpr std::array<const char*, 7> kMemClientNames = {
    kRopColorClient, kRopDepthClient, kScanoutClient, kTextureClient, kHizClient, kBinningClient, kTileStoreClient};

// A client that makes its requests of its own accord as time passes (the scan-out's line
// fetch): the memory system asks it for the cycle of its next request, lets it make them
// when that cycle comes (before any other client's request of the same cycle) and hands
// it the completions of its reads.
class SelfTimedClient {
 public:
  static constexpr uint64_t kNoRequest = ~uint64_t{0};
  virtual ~SelfTimedClient() = default;
  // The core cycle of its next request; kNoRequest: none before one of its reads completes.
  virtual uint64_t next_request_cycle() const = 0;
  // Makes the requests due at `cycle` (issue_read); afterwards next_request_cycle() > cycle.
  virtual void request(uint64_t cycle) = 0;
  // One of its reads completed at core cycle `cycle`.
  virtual void completed(uint64_t cycle) = 0;
  // Reads of its own are in flight (a completion may set its next request).
  virtual bool reads_in_flight() const = 0;
};

// What simulate reports of the memory system (add_memory_system_json).
struct MemorySystemReport {
  DramStats dram;
  std::string preset;
  uint64_t dram_end_cycle = 0;   // the last DRAM completion (posted writes included)
  uint64_t elapsed_cycles = 0;   // max(run cycles, dram_end_cycle): the utilisation's window
  double bandwidth_utilisation = 0;
  uint64_t peak_bytes_per_kcycle = 0;  // peak DRAM bytes per 1000 core cycles
};

class MemorySystem {
 public:
  explicit MemorySystem(const DramParams& p) : dram_(p) {}

  // A posted write of `bytes` at `address` made at core cycle `cycle`; split into
  // requests of at most kMaxRequestBytes.
  void post_write(MemClient c, uint64_t address, uint64_t bytes, uint64_t cycle);
  // A read made at `cycle`; its completion is waited for by wait_reads().
  void issue_read(MemClient c, uint64_t address, uint64_t bytes, uint64_t cycle);
  // Advances the DRAM until every read issued so far has completed; returns the core
  // cycle the last one completed, or nullopt when none was outstanding.
  std::optional<uint64_t> wait_reads();
  // Every request completed (the frame end): returns the last completion's cycle.
  uint64_t drain();

  // The DRAM's backlog at core cycle `now`: the cycles from `now` until every request
  // queued so far would have completed with no further arrival (DramModel::
  // drain_end_cycle; the self-timed client's later requests not counted), 0 when it
  // would be done by then. The stats' frames[].dram_backlog_cycles and frame sampling's
  // frames_simulated_backlog_in/out (docs/fidelity.md, "Frame sampling").
  uint64_t backlog_cycles(uint64_t now) const {
    const uint64_t end = dram_.drain_end_cycle();
    return end > now ? end - now : 0;
  }

  // The self-timed client (at most one: the scan-out, requests as MemClient::Scanout);
  // it must outlive the object's use.
  void attach(SelfTimedClient& c) { timed_ = &c; }

  // The clients' common clock (the SystemC model's; docs/memory.md, "Arbitration"): from
  // now on each request (the self-timed client's excepted) first calls `f(cycle)`, which
  // returns once every other client has made its requests of cycles before `cycle` (of
  // client `c`)
  // (SystemC: waits for SystemC time to reach it), so requests of decoupled clients enter
  // in time order. Empty (the default): requests enter in the order they are made.
  void set_arrival_wait(std::function<void(uint64_t cycle, MemClient c)> f) { arrival_wait_ = std::move(f); }

  // Writes every request from now on to *out in DRAMsim3's format (timing/dram_trace.h).
  void record_trace(std::ostream* out) { trace_ = out; }

  MemorySystemReport report(uint64_t run_cycles) const;
  const DramModel& dram() const { return dram_; }

  static constexpr uint64_t kMaxRequestBytes = 4096;

 private:
  void enqueue(MemClient c, uint64_t address, uint64_t bytes, bool write, uint64_t cycle);
  void take_completions();
  // One event up to core cycle `limit`: the self-timed client's next request or the
  // DRAM's next event, whichever comes first (the client at equal cycles); false when
  // neither comes at or before `limit`.
  bool step(uint64_t limit);

  DramModel dram_;
  SelfTimedClient* timed_ = nullptr;
  uint64_t floor_ = 0;  // the latest arrival or advance: no request may arrive before it
  uint64_t outstanding_reads_ = 0, next_tag_ = 0, last_completion_ = 0;
  std::optional<uint64_t> last_read_;
  std::ostream* trace_ = nullptr;
  std::function<void(uint64_t, MemClient)> arrival_wait_;  // set_arrival_wait
};

// dram_row_hit_rate, dram_bandwidth_utilisation, memory.dram.* and, per client,
// memory.clients.<name>.{bursts_read, bursts_written, row_hits, row_misses,
// row_conflicts, mean_read_latency_cycles} (docs/stats.md).
void add_memory_system_json(nlohmann::json& j, const MemorySystemReport& r);

}  // namespace rastsim
