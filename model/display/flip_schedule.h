// SPDX-License-Identifier: Apache-2.0
// Double buffering with flips at vertical blank, frame by frame (docs/scanout.md,
// "Multi-frame traces: flips at vsync"): when each frame of a multi-frame trace is
// rendered, when it becomes the displayed (front) buffer, and which frame each display
// period shows.
//
// Timeline (core cycles, as scanout_fetch.h): t = 0 is the start of vertical blanking of
// display period 0 and the moment the raster pipeline starts frame 0. Display period n
// is [n P, (n + 1) P), P = the frame period in core cycles (f_core / frame rate): its
// vertical blanking, then its active lines, read from the buffer that is front at n P.
// - Frame k renders into buffer k mod 2 (the back buffer) in c_k cycles (its frames[]
//   cycles), from s_k to e_k = s_k + c_k.
// - Its present (`frame`) flips at the first vertical blank at or after e_k: period
//   n_k = ceil(e_k / P), flip cycle F_k = n_k P; the buffer swap happens in the blanking,
//   so a period shows one whole frame: no tearing, never a half-rendered frame.
// - The present blocks until the flip (the back buffer is full, the front one is shown):
//   frame k + 1 starts at s_{k+1} = F_k. A frame of 0 cycles still waits a period
//   (n_{k+1} >= n_k + 1), so every frame is shown for at least one period.
// - Period n shows the last frame k with n_k <= n; before n_0, the initial buffer
//   (frame -1: the front buffer as the run found it).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace rastsim {

struct FrameFlip {
  double render_start = 0, render_end = 0;  // s_k, e_k, core cycles
  uint64_t flip_period = 0;                 // n_k
  double flip_cycle = 0;                    // F_k = n_k P
  int buffer = 0;                           // k mod 2: the surface it is drawn into and shown from
};

struct FlipSchedule {
  double period_cycles = 0;      // P
  std::vector<FrameFlip> frames;  // per frame of the trace
  std::vector<int> shown;         // per display period 0..n_last: the frame it shows (-1: the initial buffer)
  nlohmann::json to_json() const;  // frame_period_cycles and flips[] (docs/stats.md)
};

// The schedule for frames of `frame_cycles` core cycles each, frame period P =
// `period_cycles` (> 0). Throws std::invalid_argument when P is not positive.
FlipSchedule vsync_flips(const std::vector<uint64_t>& frame_cycles, double period_cycles);

}  // namespace rastsim
