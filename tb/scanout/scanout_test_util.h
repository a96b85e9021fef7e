// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the scan-out tests: a test-pattern framebuffer and a decode run.
#pragma once

#include <cstdint>

#include "ref/framebuffer.h"
#include "display/monitor.h"
#include "display/scanout.h"

namespace rastsim::scanout_test {

// Every byte value appears in every channel of a 256-wide or larger pattern; nearby
// pixels differ, so a one-pixel shift is a mismatch.
inline Framebuffer pattern(int w, int h) {
  Framebuffer fb(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = fb.pixel(x, y);
      p[0] = static_cast<uint8_t>(x * 7 + y * 13);
      p[1] = static_cast<uint8_t>(x ^ (y * 3));
      p[2] = static_cast<uint8_t>(x + 255 - y);
    }
  return fb;
}

// Two frames of the reference scan-out into a monitor set to `expected`.
inline MonitorResult decode(const VideoTiming& source, const VideoTiming& expected, const Dac& dac,
                            const Framebuffer& fb, int frames = 2) {
  Monitor mon(expected, dac.config());
  Scanout(source, dac, fb).run(frames, [&](const VideoSample& s) { mon.push(s); });
  return mon.finish();
}

// Number of pixels whose RGB differ between two framebuffers of the same size.
inline long long rgb_mismatches(const Framebuffer& a, const Framebuffer& b) {
  if (a.width != b.width || a.height != b.height) return -1;
  long long n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (a.pixel(x, y)[c] != b.pixel(x, y)[c]) {
          ++n;
          break;
        }
  return n;
}

}  // namespace rastsim::scanout_test
