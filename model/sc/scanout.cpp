// SPDX-License-Identifier: Apache-2.0
// Timed scan-out (see scanout.h): a line-fetch thread in the core-clock domain and a
// display thread in the pixel-clock domain, joined by the line buffer.
#include "sc/scanout.h"

#include <cmath>
#include <stdexcept>

namespace rastsim::sc {

using sc_core::sc_time;
using sc_core::SC_PS;

namespace {
// The sink's samples come from the reference scan-out: a sink alone has nothing to show.
void check_sink_has_reference(const Scanout* ref, const SampleSink& sink) {
  if (sink && !ref)
    throw std::invalid_argument("scan-out: a sample sink needs the reference frame (Scanout) to sample; none given");
}
}  // namespace

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
  report.frame_period_s = scanout_frame_period_s(p.timing);
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
  const sc_time fetch = sc_time(std::ceil(double(scanout_line_fetch_cycles(p_)) / p_.core_hz * 1e12), SC_PS);
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

}  // namespace rastsim::sc
