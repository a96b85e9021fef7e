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
#include <string>

#include <nlohmann/json.hpp>
#include <systemc>

#include "config/arch_params.h"
#include "display/scanout.h"
#include "config/video_timing.h"

namespace rastsim::sc {

// Every value comes from the config (scanout_params); none has a default here.
struct ScanoutParams {
  VideoTiming timing;
  bool single_buffered = false;  // scanout.buffering == "single"
  int line_buffer_lines = 0;     // scanout.line_buffer_lines
  int fetch_px_per_cycle = 0;    // scanout.fetch_px_per_cycle
  double core_hz = 0;            // the raster pipeline's clock (clock.core_mhz), Hz
};

// From the resolved display parameters; `core_mhz` is the raster pipeline's clock.
ScanoutParams scanout_params(const DisplayParams& display, double core_mhz);

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

// The analytic deadline (no simulation): what the module's run must agree with.
uint64_t scanout_deadline_cycles(const ScanoutParams& p);

SC_MODULE(ScanoutModule) {
  // `sink` (optional) receives every pixel clock from t = 0 through the end of the
  // frame's active region and vertical blanking, via `ref`. A sink without `ref` throws
  // std::invalid_argument.
  ScanoutModule(sc_core::sc_module_name name, const ScanoutParams& p, uint64_t raster_finish_cycles,
                const Scanout* ref = nullptr, SampleSink sink = {});
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
  const Scanout* ref_;
  SampleSink sink_;
};

// Elaborates one ScanoutModule, simulates one frame and returns its report. SystemC
// allows one elaboration per process: call once per process. This is the hook for the
// raster pipeline: pass its `cycles` (SimResult) and `core_mhz`.
ScanoutReport run_scanout(const ScanoutParams& p, uint64_t raster_finish_cycles, const Scanout* ref = nullptr,
                          const SampleSink& sink = {});

}  // namespace rastsim::sc
