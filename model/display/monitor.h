// SPDX-License-Identifier: Apache-2.0
// Virtual monitor: decodes a video signal (from the reference, SystemC or RTL scan-out)
// the way a display does, and says precisely what is wrong with it.
//
// - Captures, per pixel clock, the wire levels (hsync, vsync, BLANK) as run lengths and
//   the three levels converted back to codes by an ideal ADC (level_to_code).
// - Locks to the syncs: sync polarity is the level held for the shorter time; lines
//   start at hsync leading edges, frames at vsync leading edges. Only complete frames
//   (between two vsync leading edges) are decoded: feed at least two frames.
// - Measures every porch and sync width from the sync and BLANK edges, per line and per
//   frame, and compares them with the expected mode.
// - Samples the active region where the expected mode puts it (hsync leading edge + sync
//   + back porch; vsync trailing line + back porch), converts codes back to framebuffer
//   bytes through the palette, and rebuilds the image. An expected active pixel sent
//   blank is "no data" (an underrun, or a framebuffer smaller than the active area).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "display/dac.h"
#include "ref/framebuffer.h"
#include "display/scanout.h"
#include "config/video_timing.h"

namespace rastsim {

struct MonitorResult {
  bool locked = false;       // both syncs found and at least one complete frame decoded
  int frames_decoded = 0;
  VideoTiming measured;      // first complete frame; pixel clock = the expected one
  double line_rate_hz = 0, frame_rate_hz = 0;  // pixel clock / measured totals
  Framebuffer image;         // last complete frame, expected active size (RGB, A = 255)
  std::vector<Framebuffer> images;  // keep_images(): every complete frame decoded, in order
  std::vector<std::array<uint16_t, 3>> codes;  // same frame, the decoded DAC codes, row-major
  uint64_t no_data_pixels = 0;                 // expected active pixels that arrived blank
  uint64_t blank_level_violations = 0;         // blank pixel clocks not at 0 V (> 0.5 LSB)
  std::vector<std::string> errors;             // one clear message a fault; empty = matches
  bool ok() const { return errors.empty(); }
};

class Monitor {
 public:
  // `expected`: the mode the monitor is set to (as a display's mode table); its pixel
  // clock is the sample clock. `dac`: bits and full scale of the receiver's ADC, and the
  // palette used to turn codes back into framebuffer bytes (nonlinearity is ignored).
  Monitor(const VideoTiming& expected, const DacConfig& dac);
  // One pixel clock. Reads hsync, vsync, blank and the levels; not the codes.
  void push(const VideoSample& s);
  MonitorResult finish() const;
  // finish() also returns every decoded frame's image (MonitorResult::images; off by
  // default: a long recording would hold them all).
  void keep_images(bool on) { keep_images_ = on; }
  long long samples() const { return n_; }

  struct Runs {  // run-length record of one wire: start sample and level of each run
    std::vector<long long> start;
    std::vector<uint8_t> level;
    void push(bool v, long long t) {
      if (level.empty() || level.back() != v) start.push_back(t), level.push_back(v);
    }
  };

 private:
  VideoTiming exp_;
  DacConfig dac_cfg_;
  Dac palette_;  // ideal DAC with the same palette, for the inverse lookup
  double half_lsb_;
  long long n_ = 0;
  bool keep_images_ = false;
  Runs hs_, vs_, de_;
  std::vector<uint32_t> px_;  // per sample: R | G << 10 | B << 20 | DE << 30
  long long first_blank_violation_ = -1;
  uint64_t blank_level_violations_ = 0;
};

}  // namespace rastsim
