// SPDX-License-Identifier: Apache-2.0
// Timed scan-out: the display side of the framebuffer, in its own pixel-clock domain.
//
//   raster pipeline --(frame done at T_r)--> line fetch (core clock, fetch_px_per_cycle)
//     --> line buffer (sc_fifo, scanout.line_buffer_lines) --> pixel side (pixel clock)
//
// Timeline: t = 0 is the start of vertical blanking (line v_active, hcount 0) before the
// frame under test, and the moment the raster pipeline starts drawing it. The frame's
// active line y starts at t_y = (v_total - v_active + y) * h_total / f_pixel.
// - single buffering: the raster draws into the buffer being shown; the fetch of a line
//   may start only at T_r (the raster writes in no particular line order). A line whose
//   data is not in the line buffer at t_y is an underrun: sent blank, counted.
// - double buffering: the raster draws the back buffer while the front one is shown;
//   the swap happens at the next vertical blank. Late raster = a repeated frame, never
//   an underrun.
// Deadline: frame_deadline_met = T_r <= deadline, with deadline = t_0 minus one line
// fetch (single) or one frame period (double), in core cycles.
//
// Cost: per line by default (one wait a line); per pixel clock only when a sample sink
// is given (waveform or DAC output asked for), then through the reference Scanout.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>
#include <systemc>

#include "display/scanout.h"
#include "display/scanout_fetch.h"

namespace rastsim::sc {

// The timing parameters, the deadline and the line fetch as a DRAM client are plain C++
// (display/scanout_fetch.h, namespace rastsim), shared with the RTL testbench.

struct ScanoutReport {
  uint64_t frame_time_cycles = 0;     // raster finish time T_r, core cycles
  uint64_t deadline_cycles = 0;       // latest T_r that shows the frame whole, core cycles
  bool frame_deadline_met = false;    // frame_time_cycles <= deadline_cycles
  uint64_t lines_fetched = 0;         // active lines that reached the line buffer in time
  uint64_t underrun_lines = 0;        // active lines sent blank (single buffering)
  uint64_t underrun_pixels = 0;
  bool frame_repeated = false;        // double buffering missed the swap
  uint64_t pixel_clocks = 0;          // simulated, from t = 0 to the end of the frame
  double frame_period_s = 0;
  nlohmann::json to_json() const;
};

SC_MODULE(ScanoutModule) {
  // `sink` (optional) receives every pixel clock from t = 0 through the end of the
  // frame's active region and vertical blanking, via `ref`. A sink without `ref` throws
  // std::invalid_argument.
  ScanoutModule(sc_core::sc_module_name name, const ScanoutParams& p, uint64_t raster_finish_cycles,
                const Scanout* ref = nullptr, SampleSink sink = {});
  // Active lines the memory system did not deliver in time (simulate's
  // memory.clients.scanout.underrun_line_list, memory.model = "dram"): sent blank and
  // counted as underruns too.
  void set_memory_underruns(const std::vector<int>& lines);
  SC_HAS_PROCESS(ScanoutModule);
  ScanoutReport report;

 private:
  void fetch_thread();    // core-clock side: fills the line buffer
  void display_thread();  // pixel-clock side: consumes lines (or pixels)
  sc_core::sc_time line_start(long long line) const;  // absolute start of line index
  ScanoutParams p_;
  sc_core::sc_time t_ready_;
  sc_core::sc_fifo<int> line_buffer_;
  int next_needed_ = 0;  // the active line the display reads next
  std::vector<bool> memory_underrun_;  // by active line: set_memory_underruns
  const Scanout* ref_;
  SampleSink sink_;
};

// Elaborates one ScanoutModule, simulates one frame and returns its report. SystemC
// allows one elaboration per process: call once per process. This is the hook for the
// raster pipeline: pass its `cycles` (SimResult) and `core_mhz`.
// `memory_underruns`: ScanoutModule::set_memory_underruns.
ScanoutReport run_scanout(const ScanoutParams& p, uint64_t raster_finish_cycles, const Scanout* ref = nullptr,
                          const SampleSink& sink = {}, const std::vector<int>& memory_underruns = {});

}  // namespace rastsim::sc
