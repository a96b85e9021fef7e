// SPDX-License-Identifier: Apache-2.0
// Reference scan-out and the VCD writer of the video signal.
#include "display/scanout.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rastsim {

VideoSample Scanout::sample(int h, int v, bool has_data) const {
  VideoSample s;
  // Sync pulses: [active + front porch, active + front porch + sync) on each axis.
  const int hs0 = t_.h_active + t_.h_front_porch, vs0 = t_.v_active + t_.v_front_porch;
  const bool hs_on = h >= hs0 && h < hs0 + t_.h_sync;
  const bool vs_on = v >= vs0 && v < vs0 + t_.v_sync;
  s.hsync = hs_on == t_.h_sync_positive;
  s.vsync = vs_on == t_.v_sync_positive;
  const bool active = h < t_.h_active && v < t_.v_active;
  if (!active || !has_data || h >= fb_.width || v >= fb_.height) return s;  // blank: 0 V
  s.blank = false;
  const uint8_t* p = fb_.pixel(h, v);
  for (int c = 0; c < 3; ++c) {
    s.code[c] = dac_.code(p[c]);
    s.volts[c] = static_cast<float>(dac_.volts(c, s.code[c]));
  }
  return s;
}

void Scanout::run(int frames, const SampleSink& sink) const {
  // The counters wrap after active + porches + sync, as a hardware timing generator
  // built from those four values does; a mode whose stated total disagrees shows up in
  // the monitor as a wrong measured total.
  const int hp = t_.h_active + t_.h_front_porch + t_.h_sync + t_.h_back_porch;
  const int vp = t_.v_active + t_.v_front_porch + t_.v_sync + t_.v_back_porch;
  for (int f = 0; f < frames; ++f)
    for (int v = 0; v < vp; ++v)
      for (int h = 0; h < hp; ++h) sink(sample(h, v));
}

// ---- VCD ----

VideoVcdWriter::VideoVcdWriter(const std::string& path, double pixel_clock_hz, int bits, long long first_sample,
                               long long max_samples)
    : file_(path), os_(file_.stream()), ps_per_sample_(1e12 / pixel_clock_hz), bits_(bits), first_(first_sample),
      max_(max_samples) {
  os_ << "$date rastsim scanout $end\n$version rastsim $end\n$timescale 1ps $end\n"
      << "$scope module video $end\n"
      << "$var wire 1 h hsync $end\n$var wire 1 v vsync $end\n$var wire 1 k blank $end\n"
      << "$var wire " << bits << " R code_r [" << bits - 1 << ":0] $end\n"
      << "$var wire " << bits << " G code_g [" << bits - 1 << ":0] $end\n"
      << "$var wire " << bits << " B code_b [" << bits - 1 << ":0] $end\n"
      << "$var real 64 r level_r $end\n$var real 64 g level_g $end\n$var real 64 b level_b $end\n"
      << "$upscope $end\n$enddefinitions $end\n";
}

void VideoVcdWriter::push(const VideoSample& s) {
  const long long i = n_++;
  if (i < first_ || (max_ >= 0 && i >= first_ + max_)) return;
  const bool all = !have_prev_;
  bool stamped = false;
  auto stamp = [&] {
    if (!stamped) os_ << '#' << std::llround((i - first_) * ps_per_sample_) << '\n';
    stamped = true;
  };
  auto bit = [&](bool now, bool before, char id) {
    if (all || now != before) stamp(), os_ << (now ? '1' : '0') << id << '\n';
  };
  bit(s.hsync, prev_.hsync, 'h');
  bit(s.vsync, prev_.vsync, 'v');
  bit(s.blank, prev_.blank, 'k');
  const char code_id[3] = {'R', 'G', 'B'}, level_id[3] = {'r', 'g', 'b'};
  for (int c = 0; c < 3; ++c) {
    if (all || s.code[c] != prev_.code[c]) {
      stamp();
      os_ << 'b';
      for (int b = bits_ - 1; b >= 0; --b) os_ << ((s.code[c] >> b) & 1);
      os_ << ' ' << code_id[c] << '\n';
    }
    if (all || s.volts[c] != prev_.volts[c]) stamp(), os_ << 'r' << s.volts[c] << ' ' << level_id[c] << '\n';
  }
  prev_ = s;
  have_prev_ = true;
}

void VideoVcdWriter::close() {
  const long long end = (max_ >= 0 ? std::min(n_, first_ + max_) : n_) - first_;
  os_ << '#' << std::llround(std::max(end, 0LL) * ps_per_sample_) << '\n';
  file_.commit();
}

}  // namespace rastsim
