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
#include <deque>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <systemc>

#include "config/arch_params.h"
#include "display/scanout.h"
#include "config/video_timing.h"
#include "ref/memory/memory_params.h"
#include "ref/memory/surface_layout.h"
#include "timing/memory_system.h"

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

// ---- The line fetch as a DRAM client (memory.model = "dram"; docs/scanout.md, "Scan-out
// as a memory client") ----
//
// In `simulate`, the shown buffer is read from the same DRAM the ROP draws into, through
// MemorySystem as client `scanout`, on the timeline above (t = 0: vertical blanking and
// the raster's start). Rules, in core cycles:
// - line y is due at D_y = floor(t_y f_core); it is shown if its fetch ends at or before D_y;
// - the fetch of a line starts when the previous fetch has ended, a line-buffer slot is
//   free (scanout.line_buffer_lines lines fetched and not yet due hold every slot; a
//   line's slot frees at its D_y) and, with single buffering, at T_r (the raster's end);
// - a line whose D_y has passed when its fetch could start is skipped (an underrun);
// - a fetch issues one read a run of consecutive addresses of the line (ScanoutSurface)
//   at its start s, and ends at s + max(ceil(h_active / fetch_px_per_cycle), last read's
//   completion + 1 - s) (timing/memory_timing.h, as a ROP transaction).

// Where the shown image lies: a one-sample RGBA8 surface of memory.fb_layout. Single
// buffering with one sample: the colour surface the ROP draws (memory.color_base).
// Otherwise (the front buffer of double buffering, or the resolved image of
// raster.samples > 1) the next 4 KiB boundary after the colour surface. Throws
// std::invalid_argument naming memory.depth_base when it would overlap the depth surface.
SurfaceLayout scanout_surface(const MemoryParams& m, int width, int height, int samples, int depth_bits,
                              bool single_buffered);

struct ScanoutFetchReport {
  uint64_t bytes_read = 0;      // bytes requested (DRAM bursts: memory.clients.scanout.bursts_read)
  uint64_t reads = 0;           // read requests (one a run of consecutive addresses)
  uint64_t lines_fetched = 0;   // active lines in the line buffer by their due cycle
  uint64_t underrun_lines = 0;  // active lines sent blank: fetched late or skipped
  uint64_t underrun_pixels = 0;
  int first_underrun_line = -1;
  uint64_t last_line_end = 0;     // core cycle the last fetch ended
  uint64_t max_line_cycles = 0;   // longest fetch, start to end
  uint64_t shown_base = 0;        // the shown surface's base address
  std::vector<int> underrun_line_list;  // the active lines sent blank, ascending
  nlohmann::json to_json() const;
};

class ScanoutFetch;
// simulate's scan-out client on `mem` (memory.model = "dram"), attached to it and, with
// double buffering, started at cycle 0; null (no client) when the config's display does
// not resolve (DisplayParams::resolve: simulate then reports frame_deadline_error).
// Elaborated once a process, as the pipeline: the object is kept.
ScanoutFetch* attach_scanout_fetch(MemorySystem& mem, const ArchParams& arch);

class ScanoutFetch : public SelfTimedClient {
 public:
  ScanoutFetch(MemorySystem& mem, const ScanoutParams& p, const SurfaceLayout& shown);
  // The shown buffer is complete (double buffering: 0; single: T_r): fetching may start.
  void start(uint64_t cycle);
  // The raster pipeline's frame ended at `cycle` (T_r): starts a single-buffered fetch.
  void raster_done(uint64_t cycle) {
    if (p_.single_buffered) start(cycle);
  }
  uint64_t next_request_cycle() const override { return next_request_; }
  void request(uint64_t cycle) override;
  void completed(uint64_t cycle) override;
  bool reads_in_flight() const override { return reads_in_flight_ > 0; }
  const ScanoutFetchReport& report() const { return report_; }
  // D_y: the core cycle active line y is due at.
  uint64_t due_cycle(int y) const;

 private:
  void schedule(uint64_t earliest);  // the next line's start, from `earliest` on
  void count_underrun();             // line_ is sent blank
  MemorySystem& mem_;
  ScanoutParams p_;
  SurfaceLayout shown_;
  uint64_t fetch_cycles_;
  int line_ = 0;                     // the line being (or next to be) fetched
  uint64_t next_request_ = kNoRequest;
  uint64_t line_start_ = 0, last_fill_ = 0;
  uint64_t reads_in_flight_ = 0;
  std::deque<uint64_t> buffered_;    // due cycles of fetched lines not yet due, ascending
  ScanoutFetchReport report_;
};

}  // namespace rastsim::sc
