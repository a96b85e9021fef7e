// SPDX-License-Identifier: Apache-2.0
// Double buffering with flips at vertical blank (display/flip_schedule.h), on schedules
// worked by hand from the rule: n_k = ceil(e_k / P) (at least n_{k-1} + 1), F_k = n_k P,
// s_{k+1} = F_k, period n shows the last frame flipped at or before it.
#include <gtest/gtest.h>

#include "display/flip_schedule.h"

namespace rastsim {
namespace {

TEST(FlipSchedule, HandWorked) {
  // P = 100. Frame 0: 0..30, flips at 100 (period 1). Frame 1: 100..350, flips at 400.
  // Frame 2 takes 0 cycles: 400..400 would flip at period 4, which frame 1 took: period 5.
  // Frame 3: 500..600 flips exactly at 600 (ends on the vertical blank: shown from it).
  const FlipSchedule s = vsync_flips({30, 250, 0, 100}, 100.0);
  ASSERT_EQ(s.frames.size(), 4u);
  const double start[] = {0, 100, 400, 500}, end[] = {30, 350, 400, 600};
  const uint64_t period[] = {1, 4, 5, 6};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(s.frames[k].render_start, start[k]) << k;
    EXPECT_DOUBLE_EQ(s.frames[k].render_end, end[k]) << k;
    EXPECT_EQ(s.frames[k].flip_period, period[k]) << k;
    EXPECT_DOUBLE_EQ(s.frames[k].flip_cycle, 100.0 * double(period[k])) << k;
    EXPECT_EQ(s.frames[k].buffer, int(k % 2)) << k;
  }
  EXPECT_EQ(s.shown, (std::vector<int>{-1, 0, 0, 0, 1, 2, 3}));
}

TEST(FlipSchedule, UntimedFramesFlipAtEachVerticalBlank) {
  const FlipSchedule s = vsync_flips({0, 0, 0}, 420000.0);
  EXPECT_EQ(s.shown, (std::vector<int>{0, 1, 2}));
}

TEST(FlipSchedule, NeverShowsAFrameBeforeItsRenderingEnds) {
  // Every flip is at or after its frame's end, on a vertical blank, in frame order.
  const std::vector<uint64_t> c = {17, 1, 999, 250, 250, 3, 0, 1200};
  const FlipSchedule s = vsync_flips(c, 250.0);
  for (size_t k = 0; k < c.size(); ++k) {
    EXPECT_GE(s.frames[k].flip_cycle, s.frames[k].render_end) << k;
    if (k > 0) {
      EXPECT_GT(s.frames[k].flip_period, s.frames[k - 1].flip_period) << k;
    }
  }
  EXPECT_THROW(vsync_flips(c, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace rastsim
