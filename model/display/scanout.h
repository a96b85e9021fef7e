// SPDX-License-Identifier: Apache-2.0
// Scan-out (reference, untimed): the framebuffer read in raster order and turned, one
// pixel clock at a time, into the video signal: hsync, vsync, BLANK and three levels.
//
// - Position (hcount, vcount) follows the counter convention of video_timing.h.
// - Active pixel (x, y) = (hcount, vcount) reads framebuffer pixel (x, y); a framebuffer
//   larger than the active area is cropped to its top-left corner.
// - A pixel with no data (outside a framebuffer smaller than the active area, or a line
//   the timed model reports as underrun) is sent blank: BLANK high, 0 V. The syncs never
//   move, so the monitor sees the missing data where it expected active pixels.
// - Levels: palette lookup then the DAC's transfer curve (dac.h); blank is 0 V.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>

#include "display/dac.h"
#include "ref/framebuffer.h"
#include "config/video_timing.h"
#include "util/atomic_file.h"

namespace rastsim {

// One pixel clock of the video signal.
struct VideoSample {
  bool hsync = false, vsync = false;  // wire levels, polarity applied (true = high)
  bool blank = true;                  // BLANK (inverse of data enable): DAC output held at 0 V
  std::array<uint16_t, 3> code{};     // DAC input codes R, G, B (0 while blank)
  std::array<float, 3> volts{};       // DAC output levels R, G, B into the load, V
  bool operator==(const VideoSample&) const = default;
};

using SampleSink = std::function<void(const VideoSample&)>;

class Scanout {
 public:
  // Keeps references: the timing, DAC and framebuffer must outlive the scan-out.
  Scanout(const VideoTiming& t, const Dac& dac, const Framebuffer& fb) : t_(t), dac_(dac), fb_(fb) {}

  // The sample at (hcount, vcount); `has_data` false sends an active pixel blank.
  VideoSample sample(int hcount, int vcount, bool has_data = true) const;
  // `frames` whole frames from (0, 0), one sink call a pixel clock.
  void run(int frames, const SampleSink& sink) const;

  const VideoTiming& timing() const { return t_; }
  const Dac& dac() const { return dac_; }

 private:
  const VideoTiming& t_;
  const Dac& dac_;
  const Framebuffer& fb_;
};

// Writes a video signal as VCD: hsync, vsync, blank, the codes and the levels (real
// variables, volts), one timestamp a pixel clock (timescale 1 ps, rounded). Only changes
// are written. Samples outside [first_sample, first_sample + max_samples) are skipped.
// The file appears at close() (a temporary until then, util/atomic_file.h): a writer
// destroyed unclosed, by an error, leaves none.
class VideoVcdWriter {
 public:
  VideoVcdWriter(const std::string& path, double pixel_clock_hz, int bits, long long first_sample = 0,
                 long long max_samples = -1);
  void push(const VideoSample& s);
  // Flushes and checks the stream, then renames it into place; throws std::runtime_error
  // naming the file.
  void close();

 private:
  AtomicFile file_;
  std::ofstream& os_;
  double ps_per_sample_;
  int bits_;
  long long n_ = 0, first_, max_;
  bool have_prev_ = false;
  VideoSample prev_;
};

}  // namespace rastsim
