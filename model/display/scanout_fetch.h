// SPDX-License-Identifier: Apache-2.0
// The scan-out's timing parameters and its line fetch as a DRAM client, plain C++ (no
// SystemC): the SystemC scan-out (sc/scanout.h) and `simulate` run them, and so does the
// RTL testbench (rtlsim/tb_rop_memory.h) on the same memory system (timing/memory_system.h).
//
// Timeline: t = 0 is the start of vertical blanking (line v_active, hcount 0) before the
// frame under test, and the moment the raster pipeline starts drawing it. The frame's
// active line y starts at t_y = (v_total - v_active + y) * h_total / f_pixel.
// - single buffering: the raster draws into the buffer being shown; the fetch of a line
//   may start only at T_r (the raster's end: it writes in no particular line order).
// - double buffering: the raster draws the back buffer while the front one is shown,
//   complete from t = 0.
// Deadline: T_r <= deadline, with deadline = t_0 minus one line fetch (single) or one
// frame period (double), in core cycles.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "config/video_timing.h"
#include "ref/memory/memory_params.h"
#include "ref/memory/surface_layout.h"
#include "ref/raster_state.h"
#include "timing/memory_system.h"

namespace rastsim {

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
// The config's display and core clock; nullopt when the display does not resolve
// (DisplayParams::resolve: a config that only renders has no display to feed).
std::optional<ScanoutParams> scanout_params_if_display(const ArchParams& arch);

// Core cycles one line's fetch takes at least: ceil(h_active / fetch_px_per_cycle).
uint64_t scanout_line_fetch_cycles(const ScanoutParams& p);
// One frame's period (v_total * h_total pixel clocks), seconds.
double scanout_frame_period_s(const VideoTiming& t);
// t_y: when active line y starts, seconds from t = 0.
double scanout_line_due_seconds(const VideoTiming& t, int y);
// The analytic deadline (no simulation), core cycles: the latest T_r that shows the frame whole.
uint64_t scanout_deadline_cycles(const ScanoutParams& p);

// ---- The line fetch as a DRAM client (memory.model = "dram"; docs/scanout.md, "Scan-out
// as a memory client") ----
//
// The shown buffer is read from the same DRAM the ROP draws into, through MemorySystem as
// client `scanout`, on the timeline above. Rules, in core cycles:
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

// The report's stats keys beside add_memory_system_json's: memory.clients.scanout.* and
// scanout_underrun_lines (docs/stats.md), as simulate and cosim --stats write them.
void add_scanout_fetch_json(nlohmann::json& j, const ScanoutFetchReport& r);

class ScanoutFetch : public SelfTimedClient {
 public:
  ScanoutFetch(MemorySystem& mem, const ScanoutParams& p, const SurfaceLayout& shown);
  // The shown buffer is complete (double buffering: 0; single: T_r): fetching may start.
  void start(uint64_t cycle);
  // Before start(), double buffering: this run's cycle 0 is cycle `phase` of the timeline
  // above (frame sampling: a segment's estimated start in the full run, whose fetch starts
  // at its cycle 0; docs/fidelity.md, "Frame sampling"). The lines due by then are past
  // (neither fetched nor counted), the line buffer holds the lines whose fetch the full
  // timeline has started by then (line y < line_buffer_lines from cycle 0, line y at
  // D_{y - line_buffer_lines}), and the rest are fetched as usual, due at D_y - phase.
  // A phase past the last line's due leaves nothing to fetch, as the full run then has.
  void set_phase(uint64_t phase);
  // The raster pipeline's frame ended at `cycle` (T_r): starts a single-buffered fetch.
  void raster_done(uint64_t cycle) {
    if (p_.single_buffered) start(cycle);
  }
  uint64_t next_request_cycle() const override { return next_request_; }
  void request(uint64_t cycle) override;
  void completed(uint64_t cycle) override;
  bool reads_in_flight() const override { return reads_in_flight_ > 0; }
  const ScanoutFetchReport& report() const { return report_; }
  // D_y: the core cycle active line y is due at (this run's: minus the phase).
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
  uint64_t phase_ = 0;               // set_phase's: the timeline's cycle at this run's 0
  uint64_t reads_in_flight_ = 0;
  std::deque<uint64_t> buffered_;    // due cycles of fetched lines not yet due, ascending
  ScanoutFetchReport report_;
};

// The scan-out client on `mem` (memory.model = "dram") reading `raster`'s shown buffer,
// attached to it and, with double buffering, started at cycle 0. Attach it before any
// other client's first request: its requests of a cycle go first. It must outlive its use
// by `mem`.
// `phase`: ScanoutFetch::set_phase's (double buffering only; 0: the timeline's start).
std::unique_ptr<ScanoutFetch> attach_scanout_fetch(MemorySystem& mem, const ScanoutParams& p, const MemoryParams& m,
                                                   const RasterState& raster, uint64_t phase = 0);
// As above from the run's config; null (no client) when the display does not resolve
// (scanout_params_if_display).
std::unique_ptr<ScanoutFetch> attach_scanout_fetch(MemorySystem& mem, const ArchParams& arch, uint64_t phase = 0);

}  // namespace rastsim
