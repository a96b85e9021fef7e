// SPDX-License-Identifier: Apache-2.0
// `rastsim dram-replay TRACE`: a DRAMsim3-format trace (timing/dram_trace.h) through the
// DRAM model (timing/dram.h) of the config's memory.preset and dram.* keys; prints the
// memory stats as JSON. The model runs with its core clock equal to the DRAM clock, so
// the trace's cycles, the latencies and --cycles are DRAM clocks, as DRAMsim3 counts them
// (docs/memory.md, "Against DRAMsim3").
#include <fstream>
#include <iostream>

#include "common.h"
#include "timing/dram_trace.h"

namespace rastsim::app {

namespace {

struct DramReplayOptions {
  ConfigOptions config;
  std::string trace_path, stats_path = "-";
  uint64_t cycles = 0;  // stop here (0: when the trace is done)
  bool quiet = false;
};

// One client's figures under the stats keys; utilisation over `elapsed` cycles.
nlohmann::json client_json(const DramModel& m, const DramClientStats& s, uint64_t elapsed) {
  return {{"dram_bytes_read", s.bytes_read},
          {"dram_bytes_written", s.bytes_written},
          {"dram_row_hits", s.row_hits},
          {"dram_row_misses", s.row_misses},
          {"dram_row_conflicts", s.row_conflicts},
          {"dram_row_hit_rate", s.row_hit_rate()},
          {"dram_bandwidth_utilisation", m.bandwidth_utilisation(s.data_bus_clocks, elapsed)},
          {"dram_read_latency_mean_cycles",
           s.requests_read ? double(s.read_latency_cycles) / double(s.requests_read) : 0.0}};
}

// Replays every line arriving before `stop` (kNoEvent: all), then runs the model to
// `stop` or until idle; returns the cycle the run ends at.
uint64_t replay(DramModel& m, const std::vector<DramTraceLine>& lines, uint64_t stop) {
  uint64_t now = 0;
  auto run_until = [&](uint64_t limit) {
    for (uint64_t at = m.next_event(); at != DramModel::kNoEvent && at <= limit; at = m.next_event()) {
      m.advance_to(at);
      for (const DramCompletion& c : m.take_completions()) now = std::max(now, c.cycle);
    }
  };
  for (size_t i = 0; i < lines.size() && lines[i].clock < stop; ++i) {
    run_until(lines[i].clock);
    m.enqueue({lines[i].address, lines[i].write, uint32_t(m.params().burst_bytes()), 0, i}, lines[i].clock);
    now = std::max(now, lines[i].clock);
  }
  run_until(stop);
  if (stop != DramModel::kNoEvent) m.advance_to(stop), now = stop;
  return now;
}

void run_dram_replay_command(const DramReplayOptions& o) {
  DramParams p = resolve_arch(o.config).dram;
  p.core_khz = p.dram_khz;  // trace cycles are DRAM clocks
  std::ifstream in(o.trace_path);
  if (!in) throw std::runtime_error("cannot read " + o.trace_path);
  const std::vector<DramTraceLine> lines = read_dram_trace(in, o.trace_path);
  DramModel m(p);
  const uint64_t elapsed = replay(m, lines, o.cycles ? o.cycles : DramModel::kNoEvent);
  const DramStats& s = m.stats();
  nlohmann::json j = client_json(m, s.total(), elapsed);
  j["memory"] = {{"preset", p.preset},
                 {"address_map", address_map_name(p.address_map)},
                 {"page_policy", p.page_policy == PagePolicy::Open ? "open" : "closed"},
                 {"requests", lines.size()},
                 {"elapsed_clocks", elapsed},
                 {"peak_bytes_per_clock", double(p.channels) * p.bus_bits / 8 * p.transfers_per_clock},
                 {"dram_activates", s.activates},
                 {"dram_refreshes", s.refreshes},
                 {"clients", {{"trace", client_json(m, s.clients.empty() ? DramClientStats{} : s.clients[0], elapsed)}}}};
  write_json(o.stats_path, j);
  summary_stream(o.stats_path, o.quiet)
      << "dram-replay: " << o.trace_path << ", " << lines.size() << " requests on " << p.preset << " in " << elapsed
      << " clocks: row hit rate " << j["dram_row_hit_rate"].get<double>() << ", bandwidth utilisation "
      << j["dram_bandwidth_utilisation"].get<double>() << "\n";
}

}  // namespace

void register_dram_replay(CLI::App& app) {
  auto* cmd = app.add_subcommand("dram-replay",
                                 "Replay a DRAMsim3-format trace (0x<address> READ|WRITE <DRAM clock>, one burst a "
                                 "line) through the DRAM model of memory.preset and dram.*; print its stats JSON "
                                 "(docs/memory.md)");
  static DramReplayOptions o;
  add_config_options(cmd, o.config);
  cmd->add_option("trace", o.trace_path, "The trace file")->required();
  cmd->add_option("--stats", o.stats_path, "Stats JSON to write ('-': stdout)")->capture_default_str();
  cmd->add_option("--cycles", o.cycles,
                  "Stop after this many DRAM clocks, as DRAMsim3's -c (0: when every request is done)")
      ->capture_default_str();
  add_quiet_flag(cmd, o.quiet, "the summary line");
  cmd->callback([] { run_dram_replay_command(o); });
}

}  // namespace rastsim::app
