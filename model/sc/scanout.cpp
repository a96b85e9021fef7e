// SPDX-License-Identifier: Apache-2.0
// Timed scan-out (see scanout.h): a line-fetch thread in the core-clock domain and a
// display thread in the pixel-clock domain, joined by the line buffer.
#include "sc/scanout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "config/timing_params.h"
#include "ref/memory/rop_memory.h"
#include "timing/memory_timing.h"

namespace rastsim::sc {

using sc_core::sc_time;
using sc_core::SC_PS;

ScanoutParams scanout_params(const DisplayParams& d, double core_mhz) {
  ScanoutParams p;
  p.timing = d.video;
  p.single_buffered = d.single_buffered;
  p.line_buffer_lines = d.line_buffer_lines;
  p.fetch_px_per_cycle = d.fetch_px_per_cycle;
  p.core_hz = core_mhz * 1e6;
  return p;
}

namespace {
// The sink's samples come from the reference scan-out: a sink alone has nothing to show.
void check_sink_has_reference(const Scanout* ref, const SampleSink& sink) {
  if (sink && !ref)
    throw std::invalid_argument("scan-out: a sample sink needs the reference frame (Scanout) to sample; none given");
}

uint64_t fetch_cycles(const ScanoutParams& p) {
  return ceil_div(uint64_t(p.timing.h_active), uint64_t(p.fetch_px_per_cycle));
}
double frame_period_s(const VideoTiming& t) { return double(t.pixels_per_frame()) / t.pixel_clock_hz; }
// t_y: when active line y starts, seconds from the start of the vertical blanking before it.
double line_due_seconds(const VideoTiming& t, int y) {
  return double(t.v_total - t.v_active + y) * t.h_total / t.pixel_clock_hz;
}
}  // namespace

uint64_t scanout_deadline_cycles(const ScanoutParams& p) {
  const VideoTiming& t = p.timing;
  if (!p.single_buffered) return static_cast<uint64_t>(std::floor(frame_period_s(t) * p.core_hz));
  // Line 0 is needed after the vertical blanking; its fetch must have finished by then.
  const double c = std::floor(line_due_seconds(t, 0) * p.core_hz) - double(fetch_cycles(p));
  return c < 0 ? 0 : static_cast<uint64_t>(c);
}

nlohmann::json ScanoutReport::to_json() const {
  return {{"frame_time_cycles", frame_time_cycles}, {"deadline_cycles", deadline_cycles},
          {"frame_deadline_met", frame_deadline_met}, {"lines_fetched", lines_fetched},
          {"underrun_lines", underrun_lines}, {"underrun_pixels", underrun_pixels},
          {"frame_repeated", frame_repeated}, {"pixel_clocks", pixel_clocks},
          {"frame_period_s", frame_period_s}};
}

ScanoutModule::ScanoutModule(sc_core::sc_module_name name, const ScanoutParams& p, uint64_t raster_finish_cycles,
                             const Scanout* ref, SampleSink sink)
    : sc_module(name), p_(p), line_buffer_("line_buffer", p.line_buffer_lines), ref_(ref), sink_(std::move(sink)) {
  check_sink_has_reference(ref_, sink_);
  memory_underrun_.assign(size_t(p.timing.v_active), false);
  // Time in ps; the raster finish time is rounded up to the next ps.
  t_ready_ = sc_time(std::ceil(double(raster_finish_cycles) / p.core_hz * 1e12), SC_PS);
  report.frame_time_cycles = raster_finish_cycles;
  report.deadline_cycles = scanout_deadline_cycles(p);
  report.frame_deadline_met = raster_finish_cycles <= report.deadline_cycles;
  report.frame_period_s = frame_period_s(p.timing);
  SC_THREAD(fetch_thread);
  SC_THREAD(display_thread);
}

void ScanoutModule::set_memory_underruns(const std::vector<int>& lines) {
  for (int y : lines)
    if (y >= 0 && y < p_.timing.v_active) memory_underrun_[size_t(y)] = true;
}

sc_time ScanoutModule::line_start(long long line) const {
  // Absolute, so per-line rounding never accumulates.
  return sc_time(std::round(double(line) * p_.timing.h_total / p_.timing.pixel_clock_hz * 1e12), SC_PS);
}

void ScanoutModule::fetch_thread() {
  const VideoTiming& t = p_.timing;
  // Double buffering: the front buffer is complete from t = 0. Single: only at T_r.
  if (p_.single_buffered) wait(t_ready_);
  const sc_time fetch = sc_time(std::ceil(double(fetch_cycles(p_)) / p_.core_hz * 1e12), SC_PS);
  for (int y = 0; y < t.v_active; ++y) {
    if (y < next_needed_) continue;  // its time has passed: the display sent it blank
    wait(fetch);
    line_buffer_.write(y);  // blocks while the line buffer is full
  }
}

void ScanoutModule::display_thread() {
  const VideoTiming& t = p_.timing;
  const long long blank_lines = t.v_total - t.v_active;
  // Vertical blanking before the frame: lines v_active .. v_total-1 of the previous one.
  for (long long l = 0; l < blank_lines; ++l) {
    if (sink_)
      for (int h = 0; h < t.h_total; ++h) {
        wait(sc_time(std::round((double(l) * t.h_total + h) / t.pixel_clock_hz * 1e12), SC_PS) - sc_core::sc_time_stamp());
        sink_(ref_->sample(h, int(t.v_active + l)));
      }
    else
      wait(line_start(l + 1) - sc_core::sc_time_stamp());
  }
  for (int y = 0; y < t.v_total; ++y) {
    const long long l = blank_lines + y;
    bool has_data = true;
    if (y < t.v_active) {
      // Discard lines fetched too late for their slot, then take this one if it is there.
      int got = -1;
      while (line_buffer_.nb_read(got) && got < y) {}
      next_needed_ = y + 1;
      has_data = got == y && !memory_underrun_[size_t(y)];
      if (has_data) {
        ++report.lines_fetched;
      } else {
        ++report.underrun_lines;
        report.underrun_pixels += t.h_active;
      }
    }
    if (sink_)
      for (int h = 0; h < t.h_total; ++h) {
        wait(sc_time(std::round((double(l) * t.h_total + h) / t.pixel_clock_hz * 1e12), SC_PS) - sc_core::sc_time_stamp());
        sink_(ref_->sample(h, y, has_data));
      }
    else
      wait(line_start(l + 1) - sc_core::sc_time_stamp());
  }
  report.pixel_clocks = static_cast<uint64_t>(blank_lines + t.v_total) * t.h_total;
  report.frame_repeated = !p_.single_buffered && !report.frame_deadline_met;
  sc_core::sc_stop();
}

ScanoutReport run_scanout(const ScanoutParams& p, uint64_t raster_finish_cycles, const Scanout* ref,
                          const SampleSink& sink, const std::vector<int>& memory_underruns) {
  check_sink_has_reference(ref, sink);  // before elaborating anything
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);  // "stopped by user"
  ScanoutModule m("scanout", p, raster_finish_cycles, ref, sink);
  m.set_memory_underruns(memory_underruns);
  sc_core::sc_start();
  return m.report;
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

ScanoutFetch::ScanoutFetch(MemorySystem& mem, const ScanoutParams& p, const SurfaceLayout& shown)
    : mem_(mem), p_(p), shown_(shown), fetch_cycles_(fetch_cycles(p)) {
  report_.shown_base = shown.base();
}

uint64_t ScanoutFetch::due_cycle(int y) const {
  return static_cast<uint64_t>(std::floor(line_due_seconds(p_.timing, y) * p_.core_hz));
}

ScanoutFetch* attach_scanout_fetch(MemorySystem& mem, const ArchParams& a) {
  DisplayParams d;
  try {
    d = DisplayParams::resolve(a.config);
  } catch (const std::exception&) {
    return nullptr;  // a config that only renders: no display to feed
  }
  const ScanoutParams p = scanout_params(d, a.timing.core_mhz);
  const RasterState& r = a.raster;
  auto* f = new ScanoutFetch(
      mem, p, scanout_surface(a.memory, r.fb_width, r.fb_height, r.samples, r.depth_bits, p.single_buffered));
  mem.attach(*f);
  if (!p.single_buffered) f->start(0);
  return f;
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

}  // namespace rastsim::sc
