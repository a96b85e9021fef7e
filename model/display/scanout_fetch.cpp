// SPDX-License-Identifier: Apache-2.0
// The scan-out's timing parameters and its line fetch as a DRAM client (see scanout_fetch.h).
#include "display/scanout_fetch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "config/timing_params.h"
#include "ref/memory/rop_memory.h"
#include "timing/memory_timing.h"

namespace rastsim {

ScanoutParams scanout_params(const DisplayParams& d, double core_mhz) {
  ScanoutParams p;
  p.timing = d.video;
  p.single_buffered = d.single_buffered;
  p.line_buffer_lines = d.line_buffer_lines;
  p.fetch_px_per_cycle = d.fetch_px_per_cycle;
  p.core_hz = core_mhz * 1e6;
  return p;
}

std::optional<ScanoutParams> scanout_params_if_display(const ArchParams& a) {
  DisplayParams d;
  try {
    d = DisplayParams::resolve(a.config);
  } catch (const std::exception&) {
    return std::nullopt;  // a config that only renders: no display to feed
  }
  return scanout_params(d, a.timing.core_mhz);
}

uint64_t scanout_line_fetch_cycles(const ScanoutParams& p) {
  return ceil_div(uint64_t(p.timing.h_active), uint64_t(p.fetch_px_per_cycle));
}

double scanout_frame_period_s(const VideoTiming& t) { return double(t.pixels_per_frame()) / t.pixel_clock_hz; }

double scanout_line_due_seconds(const VideoTiming& t, int y) {
  return double(t.v_total - t.v_active + y) * t.h_total / t.pixel_clock_hz;
}

uint64_t scanout_deadline_cycles(const ScanoutParams& p) {
  const VideoTiming& t = p.timing;
  if (!p.single_buffered) return static_cast<uint64_t>(std::floor(scanout_frame_period_s(t) * p.core_hz));
  // Line 0 is needed after the vertical blanking; its fetch must have finished by then.
  const double c = std::floor(scanout_line_due_seconds(t, 0) * p.core_hz) - double(scanout_line_fetch_cycles(p));
  return c < 0 ? 0 : static_cast<uint64_t>(c);
}

SurfaceLayout scanout_surface(const MemoryParams& m, int width, int height, int samples, int depth_bits,
                              bool single_buffered) {
  constexpr uint64_t kAlign = 4096;  // the alignment memory.*_base keys have
  uint64_t base = m.color_base;
  if (!single_buffered || samples > 1)
    base = (m.color_base + color_surface_layout(m, width, height, samples).footprint_bytes() + kAlign - 1) / kAlign * kAlign;
  const SurfaceLayout shown(m.layout, m.tile_width, m.tile_height, base, width, height, 1, kColorBytesPerSample);
  const SurfaceLayout depth = depth_surface_layout(m, width, height, samples, depth_bits);
  const uint64_t end = base + shown.footprint_bytes(), depth_end = depth.base() + depth.footprint_bytes();
  if (base < depth_end && depth.base() < end)
    throw std::invalid_argument(
        "memory.depth_base = " + std::to_string(depth.base()) + ": the depth surface [" + std::to_string(depth.base()) +
        ", " + std::to_string(depth_end) + ") overlaps the scan-out's shown buffer [" + std::to_string(base) + ", " +
        std::to_string(end) + "), which follows the colour surface at memory.color_base (docs/scanout.md); move "
        "memory.depth_base");
  return shown;
}

nlohmann::json ScanoutFetchReport::to_json() const {
  return {{"bytes_read", bytes_read},         {"reads", reads},
          {"lines_fetched", lines_fetched},   {"underrun_lines", underrun_lines},
          {"underrun_pixels", underrun_pixels}, {"first_underrun_line", first_underrun_line},
          {"last_line_end_cycle", last_line_end}, {"max_line_fetch_cycles", max_line_cycles},
          {"shown_base", shown_base}, {"underrun_line_list", underrun_line_list}};
}

void add_scanout_fetch_json(nlohmann::json& j, const ScanoutFetchReport& r) {
  j["memory"]["clients"][kScanoutClient].update(r.to_json());
  j["scanout_underrun_lines"] = r.underrun_lines;
}

ScanoutFetch::ScanoutFetch(MemorySystem& mem, const ScanoutParams& p, const SurfaceLayout& shown)
    : mem_(mem), p_(p), shown_(shown), fetch_cycles_(scanout_line_fetch_cycles(p)) {
  report_.shown_base = shown.base();
}

// D_y on the whole timeline (no phase), core cycles.
static uint64_t timeline_due(const ScanoutParams& p, int y) {
  return static_cast<uint64_t>(std::floor(scanout_line_due_seconds(p.timing, y) * p.core_hz));
}

uint64_t ScanoutFetch::due_cycle(int y) const { return timeline_due(p_, y) - phase_; }

void ScanoutFetch::set_phase(uint64_t phase) {
  phase_ = phase;
  const int lines = p_.timing.v_active, slots = p_.line_buffer_lines;
  line_ = 0;
  while (line_ < lines && timeline_due(p_, line_) <= phase) ++line_;  // shown before this run
  // Fetched by then on the full timeline: the first `slots` lines from cycle 0, line y
  // once line y - slots has come due and freed its slot.
  while (line_ < lines && (line_ < slots || timeline_due(p_, line_ - slots) <= phase)) buffered_.push_back(due_cycle(line_++));
}

std::unique_ptr<ScanoutFetch> attach_scanout_fetch(MemorySystem& mem, const ScanoutParams& p, const MemoryParams& m,
                                                   const RasterState& r, uint64_t phase) {
  auto f = std::make_unique<ScanoutFetch>(
      mem, p, scanout_surface(m, r.fb_width, r.fb_height, r.samples, r.depth_bits, p.single_buffered));
  mem.attach(*f);
  if (!p.single_buffered) {
    if (phase > 0) f->set_phase(phase);
    f->start(0);
  }
  return f;
}

std::unique_ptr<ScanoutFetch> attach_scanout_fetch(MemorySystem& mem, const ArchParams& a, uint64_t phase) {
  const std::optional<ScanoutParams> p = scanout_params_if_display(a);
  if (!p) return nullptr;
  return attach_scanout_fetch(mem, *p, a.memory, a.raster, phase);
}

void ScanoutFetch::count_underrun() {
  if (report_.first_underrun_line < 0) report_.first_underrun_line = line_;
  report_.underrun_line_list.push_back(line_);
  ++report_.underrun_lines;
  report_.underrun_pixels += uint64_t(p_.timing.h_active);
}

void ScanoutFetch::start(uint64_t cycle) { schedule(cycle); }

void ScanoutFetch::schedule(uint64_t earliest) {
  const size_t slots = size_t(p_.line_buffer_lines);
  for (; line_ < p_.timing.v_active; ++line_) {
    uint64_t s = earliest;
    const auto free_until = [&](uint64_t t) {
      while (!buffered_.empty() && buffered_.front() <= t) buffered_.pop_front();
    };
    free_until(s);
    if (buffered_.size() >= slots) {  // wait for the oldest of the last `slots` lines' slot
      s = std::max(s, buffered_[buffered_.size() - slots]);
      free_until(s);
    }
    if (due_cycle(line_) > s) {
      next_request_ = s;
      return;
    }
    count_underrun();  // too late to start: skipped
  }
  next_request_ = kNoRequest;
}

// One read a run of consecutive addresses along the line (the whole line when linear;
// a tile row's pixels when tiled).
void ScanoutFetch::request(uint64_t cycle) {
  next_request_ = kNoRequest;
  line_start_ = last_fill_ = cycle;
  const uint64_t bpp = uint64_t(shown_.bytes_per_sample());
  uint64_t run = 0, run_bytes = 0;
  const auto issue = [&] {
    if (run_bytes == 0) return;
    mem_.issue_read(MemClient::Scanout, run, run_bytes, cycle);
    reads_in_flight_ += (run_bytes + MemorySystem::kMaxRequestBytes - 1) / MemorySystem::kMaxRequestBytes;
    report_.bytes_read += run_bytes;
    ++report_.reads;
  };
  for (int x = 0; x < shown_.width(); ++x) {
    const uint64_t a = shown_.address_of(x, line_, 0);
    if (run_bytes > 0 && a == run + run_bytes) {
      run_bytes += bpp;
      continue;
    }
    issue();
    run = a;
    run_bytes = bpp;
  }
  issue();
}

void ScanoutFetch::completed(uint64_t cycle) {
  last_fill_ = std::max(last_fill_, cycle);
  if (--reads_in_flight_ > 0) return;
  const uint64_t cycles = memory_transaction_cycles(fetch_cycles_, line_start_, true, last_fill_);
  const uint64_t end = line_start_ + cycles;
  report_.max_line_cycles = std::max(report_.max_line_cycles, cycles);
  report_.last_line_end = end;
  const uint64_t due = due_cycle(line_);
  if (end <= due) {
    ++report_.lines_fetched;
    buffered_.push_back(due);
  } else {
    count_underrun();
  }
  ++line_;
  schedule(end);
}

}  // namespace rastsim
