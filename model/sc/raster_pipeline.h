// SPDX-License-Identifier: Apache-2.0
// The timed raster pipeline: the stages and FIFOs of timing/stage_table.h, and the one
// call that elaborates it, runs a scene through it and reports cycles and per-stage stats.
//
//   command_fetch -> prim_assembly -> tri_setup -> coarse_raster -> fine_raster
//                 -> interpolate -> rop (framebuffer)
//   interpolate -> texture -> rop                    (textured batches only)
//   command_fetch -> front_end -> prim_assembly      (clip-space commands only)
//   command_fetch -> draw2d_setup -> engine2d <-> rop (2D commands)
//
// All arithmetic is the reference model's; this layer only adds time. The framebuffer
// and fragment stream are bit-identical to ref/pipeline.h: render_scene.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "ref/memory/rop_memory.h"
#include "ref/pipeline.h"
#include "sc/command_fetch.h"
#include "timing/memory_system.h"
#include "timing/hiz_memory_port.h"
#include "timing/texture_memory_port.h"
#include "sc/scanout.h"
#include "scene/scene_io.h"
#include "config/timing_params.h"
#include "sc/tile_heat.h"
#include "sc/timeline.h"

namespace rastsim::sc {

struct SimOptions {
  std::string vcd_path;          // write a VCD of FIFO occupancy and stage state ("" = none)
  uint64_t stall_seed = 0;       // random stall injection at every FIFO write (tests)
  double stall_probability = 0;  // 0 = off
  FragmentSink on_fragment;      // every fragment leaving interpolation, in order
  // Command fetch starting each transaction: a command, or triangle k of a primitive
  // command, with the cycle (SimContext::on_fetch; the sampled level's unit boundaries).
  std::function<void(const Command& cmd, size_t triangle, uint64_t cycle)> on_fetch;
  // The ROP taking each state item of the scene, with the cycle (SimContext::on_rop_state;
  // frame sampling's frame boundaries, model/fidelity/frames.h FrameBoundary::Rop).
  std::function<void(const Command& cmd, uint64_t cycle)> on_rop_state;
  // Trace-event JSON of every stage's state and FIFO's occupancy ("" = none; sc/timeline.h),
  // quantized to fit timeline_max_events events (250,000: about 10-17 MB, docs/timeline.md).
  std::string timeline_path;
  uint64_t timeline_max_events = 250'000;
  bool heatmap = false;  // fill SimResult::heat (busy cycles per screen tile)
  bool spans = false;    // fill StageReport::spans (rastsim cosim --trace-diff)
  // Stages advance SystemC time in step with their own (SimContext::lockstep; implied by
  // a VCD or a timeline): same cycles and stats, slower; tests compare the two.
  bool lockstep = false;
  // Every DRAM request in DRAMsim3's format (timing/dram_trace.h; "" = none): needs
  // memory.model = "dram". Written atomically after a successful run.
  std::string mem_trace_path;
  // The framebuffer the ROP starts from, colour and depth (arch's size and samples; null:
  // the initial one). `--frames A:B` replays frames 0..A-1 in the reference model and
  // times frames A.. from their framebuffer (model/fidelity/frames.h).
  const Framebuffer* initial_fb = nullptr;
  // memory.model = "dram": the ROP's memory clients' state to start from (their caches'
  // lines and dirty bits, fast-clear flags: a functional run's, SceneRenderer::memory())
  // instead of empty caches after a depth clear. Frame sampling's warm-up
  // (model/fidelity/frame_sampled.h); the DRAM itself starts idle, rows closed.
  const RopMemory* warm_memory = nullptr;
  // memory.model = "dram" with a double-buffered display: the scan-out timeline's cycle at
  // this run's cycle 0 (ScanoutFetch::set_phase; 0: the display frame starts with the run).
  // Frame sampling's segments: their estimated start in the full run.
  uint64_t scanout_phase = 0;
  // memory.model = "dram": called once, before the run starts, with the run's memory
  // system, which lives through the run, so on_fetch may ask it (MemorySystem::
  // backlog_cycles: frame sampling's DRAM backlog at each frame's first fetch).
  std::function<void(const MemorySystem& memory)> on_memory_system;
  // Tests of depth.hiz_sync = lagged (tb/sc/test_sc_hiz.cpp): every Hi-Z cull and accept
  // coarse raster makes, and a planted bug (accept on blocks a tile in flight touches),
  // which the tests must catch. Never set by the tool.
  std::function<void(const SetupTriangle& t, const PixelRect& fp, HizDecision d)> on_hiz;
  bool hiz_lag_accept_busy = false;
};

struct StageReport {
  std::string name;
  uint64_t busy = 0, stalled = 0, starved = 0;  // cycles; they add up to `cycles`
  uint64_t transactions_in = 0, transactions_out = 0;
  std::vector<Span> spans;  // per transaction, when SimOptions::spans (sc/timeline.h)
  uint64_t transactions = 0;  // StageStats::transactions(): what --trace-diff's rows count
};

struct FifoReport {
  std::string name;
  int depth = 0;
  uint64_t writes = 0, reads = 0;  // equal after a run: nothing lost or left behind
};

struct SimResult {
  Framebuffer fb;                    // the ROP's own (sparse), moved here: one framebuffer a run
  RenderStats render;                // the reference model's counters (same names)
  // The ROP's framebuffer traffic (sc/rop.h, docs/microarchitecture.md "Multisampling"):
  // accesses (rop_accesses summed over every fragment), bytes moved (accesses x (4 +
  // depth bytes) + clears + resolve_bytes), and the resolve pass's cycles (0 for one
  // sample), which are the ROP's busy cycles at the end of the frame.
  uint64_t rop_accesses = 0, framebuffer_bytes = 0, resolve_cycles = 0;
  // The interpolator's reciprocal unit (sc/interpolate.h): reciprocals, busy cycles.
  uint64_t recip_reciprocals = 0, recip_busy_cycles = 0;
  uint64_t cycles = 0;               // first command to the end of the last transaction
  uint64_t cycles_lower_bound = 0;   // max over stages of fill latency + busy cycles
  std::vector<StageReport> stages;   // in pipeline order
  std::vector<FifoReport> fifos;     // in pipeline order
  double core_mhz = 0;
  double sim_wall_seconds = 0;       // elaboration + simulation
  TimelineWriteStats timeline;       // what --timeline wrote (events 0 when off)
  // --heatmap: busy cycles per tile of coarse_raster, fine_raster, interpolate and rop,
  // in that order (empty when off).
  std::vector<TileHeat> heat;
  // The timed memory system's figures (memory.model = "dram"; timing/memory_system.h), else empty.
  // render.memory holds the functional counts, equal to render's.
  std::optional<MemorySystemReport> memory;
  // The scan-out's line fetch as a memory client (display/scanout_fetch.h: ScanoutFetch), when the
  // memory system is on and the config's display resolves.
  std::optional<ScanoutFetchReport> scanout;
  // The texture cache's line fills as a memory client (timing/texture_memory_port.h), when
  // the memory system is on and a texture line was filled.
  std::optional<TextureMemoryReport> texture_memory;
  // The spilled Hi-Z table as a memory client (timing/hiz_memory_port.h), when it made a
  // request (memory.model = "dram").
  std::optional<HizMemoryReport> hiz_memory;
  // pipeline.mode = binned: the binner stage and its output FIFO (sc/binning.h; outside
  // the stage table: stages.binner, fifos.bin_fifo).
  std::optional<StageReport> binner;
  std::optional<FifoReport> bin_fifo;

  // RenderStats::to_json plus cycles, cycles_lower_bound, simulated_seconds,
  // sim_wall_seconds, simulated_cycles_per_second, rop_accesses, framebuffer_bytes,
  // resolve_cycles, recip_reciprocals, recip_busy_cycles, stages.<name>.{busy,...}
  // (stages.front_end also the front end's counters, when a clip-space primitive was
  // drawn), fifos.<name>, and with the memory system add_memory_system_json's keys.
  nlohmann::json to_json() const;
};

// Cycles one state command needs through the whole pipeline (fetch header plus one
// cycle in each later stage): what a scene without primitives or clears costs.
uint64_t fixed_latency_cycles(const TimingParams& p);

// Elaborates the pipeline for `arch` (the run's resolved config), runs `scene` through it and returns the result.
// SystemC allows one elaboration per process: call this once per process (the sweep
// and the tests run each simulation in a child process). Throws SceneError on bad input
// (the reference model's message) and ModelError (sc/model_error.h) on a fault of the
// model itself, such as a lost or reordered transaction.
SimResult simulate_scene(const Scene& scene, const ArchParams& arch, const SimOptions& opts = {});

// The same for any command source (sc/command_fetch.h): simulate_scene is this on the
// scene's commands.
SimResult simulate_commands(CommandSource source, const ArchParams& arch, const SimOptions& opts = {});

// The same on a scene file (an OBJ placed by arch.placement) streamed in batches of `batch` commands (scene_io.h
// stream_scene_ahead): the reader runs on a thread of its own, up to two batches ahead of
// command fetch, so memory stays bounded by those batches, not the file. Cycles, image and stats are simulate_scene's on the
// loaded scene. A malformed line stops the run with its SceneError (file:line), saying
// how many commands were fetched and at which cycle, when any were.
SimResult simulate_stream(const std::string& path, const ArchParams& arch, const SimOptions& opts = {},
                          size_t batch = 4096);

}  // namespace rastsim::sc
