// SPDX-License-Identifier: Apache-2.0
#include "display/flip_schedule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rastsim {

FlipSchedule vsync_flips(const std::vector<uint64_t>& frame_cycles, double period_cycles) {
  if (!(period_cycles > 0)) throw std::invalid_argument("vsync_flips: the frame period must be positive");
  FlipSchedule s;
  s.period_cycles = period_cycles;
  double start = 0;
  uint64_t last_period = 0;
  for (size_t k = 0; k < frame_cycles.size(); ++k) {
    FrameFlip f;
    f.render_start = start;
    f.render_end = start + double(frame_cycles[k]);
    f.flip_period = uint64_t(std::ceil(f.render_end / period_cycles));
    if (k > 0) f.flip_period = std::max(f.flip_period, last_period + 1);  // one flip a vertical blank
    f.flip_cycle = double(f.flip_period) * period_cycles;
    f.buffer = int(k % 2);
    s.frames.push_back(f);
    start = f.flip_cycle;  // the present returns at the flip: the next frame's back buffer is free
    last_period = f.flip_period;
  }
  s.shown.assign(s.frames.empty() ? 0 : last_period + 1, -1);
  for (size_t k = 0; k < s.frames.size(); ++k)
    for (uint64_t n = s.frames[k].flip_period; n < s.shown.size(); ++n) s.shown[n] = int(k);
  return s;
}

nlohmann::json FlipSchedule::to_json() const {
  nlohmann::json flips = nlohmann::json::array();
  for (size_t k = 0; k < frames.size(); ++k) {
    const FrameFlip& f = frames[k];
    flips.push_back({{"frame", k},
                     {"buffer", f.buffer},
                     {"render_start_cycle", f.render_start},
                     {"render_end_cycle", f.render_end},
                     {"flip_period", f.flip_period},
                     {"flip_cycle", f.flip_cycle}});
  }
  return {{"frame_period_cycles", period_cycles}, {"flips", flips}};
}

}  // namespace rastsim
