// SPDX-License-Identifier: Apache-2.0
// SystemC scan-out: the deadline check and underrun count against hand-worked numbers,
// and the per-pixel stream decoded by the virtual monitor. SystemC elaborates once per
// process: one simulation a test; ctest runs each test in its own process (by hand,
// use --gtest_filter). Not gtest_main: libsystemc owns main() and calls sc_main.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <systemc>

#include "sc/scanout.h"
#include "scanout_test_util.h"

namespace rastsim {
namespace {

// The DAC and scan-out of a default config: tests change only what they are about.
DacConfig default_dac_config() { return dac_config_from_config(Config{}); }
ScanoutParams default_params(const char* preset, double core_mhz) {
  ScanoutParams p = scanout_params(DisplayParams::resolve(Config{}), core_mhz);
  p.timing = *find_timing_preset(preset);
  return p;
}

ScanoutParams panel_single() {
  ScanoutParams p = default_params("panel", 100);
  p.single_buffered = true;
  p.line_buffer_lines = 2;
  p.fetch_px_per_cycle = 4;  // 128 px a line: 32 core cycles a fetch
  return p;
}

// Panel: a line is 160 / 1.3056 MHz = 122.549 us; line 0 is needed after the 8 blank
// lines, at 980.392 us = 98039 core cycles at 100 MHz; minus one 32-cycle fetch.
constexpr uint64_t kPanelSingleDeadline = 98039 - 32;

TEST(ScanoutSc, FastRasterMeetsDeadlineWithoutUnderrun) {
  const sc::ScanoutReport r = sc::run_scanout(panel_single(), 1000);
  EXPECT_EQ(r.deadline_cycles, kPanelSingleDeadline);
  EXPECT_TRUE(r.frame_deadline_met);
  EXPECT_EQ(r.underrun_lines, 0u);
  EXPECT_EQ(r.lines_fetched, 128u);
  EXPECT_EQ(r.pixel_clocks, (8u + 136u) * 160u);
}

TEST(ScanoutSc, RasterFinishingAtDeadlineStillInTime) {
  const sc::ScanoutReport r = sc::run_scanout(panel_single(), kPanelSingleDeadline);
  EXPECT_TRUE(r.frame_deadline_met);
  EXPECT_EQ(r.underrun_lines, 0u) << "the analytic deadline and the simulation must agree";
}

TEST(ScanoutSc, RasterJustLateUnderrunsFirstLine) {
  const sc::ScanoutReport r = sc::run_scanout(panel_single(), kPanelSingleDeadline + 2);
  EXPECT_FALSE(r.frame_deadline_met);
  EXPECT_EQ(r.underrun_lines, 1u);
}

TEST(ScanoutSc, SlowRasterUnderrunCaughtByMonitor) {
  // The raster finishes at 1.5 ms (150000 cycles). Line y starts at (8 + y) * 122.549 us:
  // y = 4 at 1470.6 us is too early, y = 5 at 1593.1 us gets its fetch (1500.32 us).
  // So lines 0..4 underrun: 5 lines, 640 pixels.
  const ScanoutParams p = panel_single();
  const Dac dac(default_dac_config());
  const Framebuffer fb = scanout_test::pattern(128, 128);
  const Scanout ref(p.timing, dac, fb);
  Monitor mon(p.timing, dac.config());
  const sc::ScanoutReport r = sc::run_scanout(p, 150000, &ref, [&](const VideoSample& s) { mon.push(s); });
  EXPECT_FALSE(r.frame_deadline_met);
  EXPECT_EQ(r.underrun_lines, 5u);
  EXPECT_EQ(r.underrun_pixels, 640u);
  const MonitorResult m = mon.finish();
  ASSERT_EQ(m.frames_decoded, 1);
  ASSERT_FALSE(m.ok());
  bool named = false;
  for (auto& e : m.errors) named |= e.find("underrun") != std::string::npos && e.find("of lines 0..4") != std::string::npos;
  EXPECT_TRUE(named) << m.errors.front();
  EXPECT_EQ(m.no_data_pixels, 640u);
  EXPECT_EQ(m.image.pixel(10, 5)[0], fb.pixel(10, 5)[0]);
}

TEST(ScanoutSc, DoubleBufferedLateRasterRepeatsFrame) {
  ScanoutParams p = panel_single();
  p.single_buffered = false;
  // One frame at exactly 60 Hz is 1/60 s = 1666666.67 cycles at 100 MHz.
  const sc::ScanoutReport r = sc::run_scanout(p, 1700000);
  EXPECT_EQ(r.deadline_cycles, 1666666u);
  EXPECT_FALSE(r.frame_deadline_met);
  EXPECT_TRUE(r.frame_repeated);
  EXPECT_EQ(r.underrun_lines, 0u);
}

TEST(ScanoutSc, PerPixelVgaStreamDecodesBitExact) {
  const ScanoutParams p = default_params("vga640x480@60", 200);
  const Dac dac(default_dac_config());
  const Framebuffer fb = scanout_test::pattern(640, 480);
  const Scanout ref(p.timing, dac, fb);
  Monitor mon(p.timing, dac.config());
  const sc::ScanoutReport r = sc::run_scanout(p, 1000000, &ref, [&](const VideoSample& s) { mon.push(s); });
  EXPECT_TRUE(r.frame_deadline_met);
  const MonitorResult m = mon.finish();
  ASSERT_TRUE(m.ok()) << m.errors.front();
  EXPECT_EQ(scanout_test::rgb_mismatches(m.image, fb), 0);
  EXPECT_EQ(m.measured.h_total, 800);
  EXPECT_EQ(m.measured.v_total, 525);
}

TEST(ScanoutSc, SinkWithoutReferenceFrameIsRejected) {
  try {
    sc::run_scanout(panel_single(), 1000, nullptr, [](const VideoSample&) {});
    FAIL() << "a sink without a reference frame was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs the reference frame"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim

int sc_main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  return RUN_ALL_TESTS();
}
