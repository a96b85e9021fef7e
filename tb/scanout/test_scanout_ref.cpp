// SPDX-License-Identifier: Apache-2.0
// Reference scan-out + virtual monitor: presets against the published standards, bit-
// exact decode with an ideal DAC, the INL bound with a nonlinear one, and the faults
// the monitor must name. Expected numbers are typed from the standards (VESA DMT /
// CEA-861) and worked by hand, never taken from the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scanout_test_util.h"
#include "config/video_timing.h"

namespace rastsim {
namespace {

// The DAC of a default config: tests change only what they are about.
DacConfig default_dac_config() { return dac_config_from_config(Config{}); }

using scanout_test::decode;
using scanout_test::pattern;
using scanout_test::rgb_mismatches;

bool has_error(const MonitorResult& r, const std::string& text) {
  return std::any_of(r.errors.begin(), r.errors.end(),
                     [&](const std::string& e) { return e.find(text) != std::string::npos; });
}

std::string all_errors(const MonitorResult& r) {
  std::string s;
  for (auto& e : r.errors) s += e + "\n";
  return s;
}

// The published numbers: active, front porch, sync, back porch, total (h then v),
// polarities, pixel clock, line rate and frame rate (rates worked out by hand:
// 25.175e6 / 800 = 31468.75 Hz, / 525 = 59.9404762 Hz).
struct Standard {
  const char* name;
  int h[5], v[5];
  bool hpos, vpos;
  double pclk_hz, line_hz, frame_hz;
};
const Standard kStandards[] = {
    {"panel", {128, 8, 16, 8, 160}, {128, 2, 2, 4, 136}, false, false, 1.3056e6, 8160.0, 60.0},
    {"vga640x480@60", {640, 16, 96, 48, 800}, {480, 10, 2, 33, 525}, false, false, 25.175e6, 31468.75, 59.9404762},
    {"720p60", {1280, 110, 40, 220, 1650}, {720, 5, 5, 20, 750}, true, true, 74.25e6, 45000.0, 60.0},
    {"1080p60", {1920, 88, 44, 148, 2200}, {1080, 4, 5, 36, 1125}, true, true, 148.5e6, 67500.0, 60.0},
};

void expect_timing(const VideoTiming& t, const Standard& s) {
  EXPECT_EQ(t.h_active, s.h[0]);
  EXPECT_EQ(t.h_front_porch, s.h[1]);
  EXPECT_EQ(t.h_sync, s.h[2]);
  EXPECT_EQ(t.h_back_porch, s.h[3]);
  EXPECT_EQ(t.h_total, s.h[4]);
  EXPECT_EQ(t.v_active, s.v[0]);
  EXPECT_EQ(t.v_front_porch, s.v[1]);
  EXPECT_EQ(t.v_sync, s.v[2]);
  EXPECT_EQ(t.v_back_porch, s.v[3]);
  EXPECT_EQ(t.v_total, s.v[4]);
  EXPECT_EQ(t.h_sync_positive, s.hpos);
  EXPECT_EQ(t.v_sync_positive, s.vpos);
}

Config config_for(const Standard& s) {
  Config cfg;
  cfg.set_from_string("display.timing", s.name, "test");
  cfg.set_from_string("display.width", std::to_string(s.h[0]), "test");
  cfg.set_from_string("display.height", std::to_string(s.v[0]), "test");
  return cfg;
}

class ScanoutPreset : public ::testing::TestWithParam<Standard> {};

TEST_P(ScanoutPreset, ConfigMatchesStandard) {
  const Standard& s = GetParam();
  const VideoTiming t = video_timing_from_config(config_for(s));
  expect_timing(t, s);
  EXPECT_DOUBLE_EQ(t.pixel_clock_hz, s.pclk_hz);
  EXPECT_NEAR(t.line_rate_hz(), s.line_hz, 1e-6);
  EXPECT_NEAR(t.frame_rate_hz(), s.frame_hz, 1e-6);
  EXPECT_TRUE(t.problems().empty());
}

TEST_P(ScanoutPreset, IdealDacDecodesBitExactWithConfiguredTimings) {
  const Standard& s = GetParam();
  const Config cfg = config_for(s);
  const VideoTiming t = video_timing_from_config(cfg);
  const Dac dac(dac_config_from_config(cfg));
  const Framebuffer fb = pattern(s.h[0], s.v[0]);
  const MonitorResult r = decode(t, t, dac, fb);
  EXPECT_TRUE(r.ok()) << all_errors(r);
  ASSERT_EQ(r.frames_decoded, 1);
  EXPECT_EQ(rgb_mismatches(r.image, fb), 0);
  EXPECT_EQ(r.no_data_pixels, 0u);
  expect_timing(r.measured, s);
  EXPECT_NEAR(r.line_rate_hz, s.line_hz, 1e-6);
  EXPECT_NEAR(r.frame_rate_hz, s.frame_hz, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Presets, ScanoutPreset, ::testing::ValuesIn(kStandards),
                         [](const auto& info) {
                           std::string n = info.param.name;
                           n.erase(std::remove_if(n.begin(), n.end(), [](char c) { return !std::isalnum(c); }), n.end());
                           return n;
                         });

TEST(ScanoutDac, IdealLevelsAreCodeTimesLsb) {
  // 8 bits, 0.700 V: LSB = 0.7 / 255 V; code 255 -> 0.700 V, code 128 -> 0.35137 V.
  const Dac dac(default_dac_config());
  EXPECT_NEAR(dac.volts(0, 255), 0.700, 1e-12);
  EXPECT_NEAR(dac.volts(1, 128), 0.7 * 128 / 255, 1e-12);
  EXPECT_EQ(dac.volts(2, 0), 0.0);
  for (int v = 0; v < 256; ++v) ASSERT_EQ(dac.code(v), v);
}

TEST(ScanoutDac, TenBitLinearPaletteRoundTrips) {
  DacConfig c = default_dac_config();
  c.bits = 10;
  const Dac dac(c);
  // round(v * 1023 / 255): 1 -> 4 (4.01), 128 -> 514 (513.5 rounds up), 255 -> 1023.
  EXPECT_EQ(dac.code(1), 4);
  EXPECT_EQ(dac.code(128), 514);
  EXPECT_EQ(dac.code(255), 1023);
  for (int v = 0; v < 256; ++v) ASSERT_EQ(dac.inverse(dac.code(v)), v);
}

TEST(ScanoutDac, MismatchModelStaysWithinConfiguredInlAndDnl) {
  for (uint64_t seed : {1u, 2u, 77u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    DacConfig c = default_dac_config();
    c.inl_lsb = 2.0, c.dnl_lsb = 0.5, c.seed = seed;
    const Dac dac(c);
    // Independent measurement from the levels alone: endpoint-fit line through codes 0
    // and 255, INL = deviation from it, DNL = step - 1 LSB.
    for (int ch = 0; ch < 3; ++ch) {
      const double v0 = dac.volts(ch, 0), v1 = dac.volts(ch, 255), lsb = (v1 - v0) / 255;
      double max_inl = 0, max_dnl = 0;
      for (int k = 0; k < 256; ++k) {
        max_inl = std::max(max_inl, std::abs((dac.volts(ch, k) - v0) / lsb - k));
        if (k) max_dnl = std::max(max_dnl, std::abs((dac.volts(ch, k) - dac.volts(ch, k - 1)) / lsb - 1));
      }
      EXPECT_LE(max_inl, 2.0 + 1e-9);
      EXPECT_LE(max_dnl, 0.5 + 1e-9);
      EXPECT_GE(max_inl, 1.0) << "the model should use a good part of its INL budget";
    }
  }
}

TEST(ScanoutDac, NonlinearDacDecodedErrorWithinInl) {
  const double inl = 2.0;
  Config cfg = config_for(kStandards[1]);  // VGA
  cfg.set_from_string("dac.inl_lsb", "2.0", "test");
  cfg.set_from_string("dac.dnl_lsb", "0.5", "test");
  cfg.set_from_string("dac.seed", "5", "test");
  const VideoTiming t = video_timing_from_config(cfg);
  const Dac dac(dac_config_from_config(cfg));
  const Framebuffer fb = pattern(640, 480);
  const MonitorResult r = decode(t, t, dac, fb);
  EXPECT_TRUE(r.ok()) << all_errors(r);
  ASSERT_EQ(r.frames_decoded, 1);
  // An ideal ADC rounds (code + INL) to the nearest code: |error| <= floor(INL + 0.5).
  int max_err = 0;
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x)
      for (int c = 0; c < 3; ++c)
        max_err = std::max(max_err, std::abs(int(r.image.pixel(x, y)[c]) - int(fb.pixel(x, y)[c])));
  EXPECT_LE(max_err, int(std::floor(inl + 0.5)));
  EXPECT_GE(max_err, 1) << "a 2 LSB INL must show in the picture";
  EXPECT_GT(rgb_mismatches(r.image, fb), 0);
}

// ---- faults ----

TEST(ScanoutFault, PorchesNotAddingUpRejectedByConfig) {
  Config cfg;
  cfg.set_from_string("display.timing", "custom", "test");
  cfg.set_from_string("display.h_back_porch_px", "10", "test");  // 128 + 8 + 16 + 10 = 162 != 160
  try {
    video_timing_from_config(cfg);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("= 162 px, but the total is 160 px"), std::string::npos) << e.what();
  }
}

TEST(ScanoutFault, PorchesNotAddingUpCaughtByMonitor) {
  VideoTiming t = *find_timing_preset("vga640x480@60");
  t.h_back_porch = 50;  // the source counts 640 + 16 + 96 + 50 = 802 clocks a line
  const Dac dac(default_dac_config());
  const MonitorResult r = decode(t, t, dac, pattern(640, 480));
  EXPECT_TRUE(has_error(r, "porches do not add up")) << all_errors(r);
  EXPECT_TRUE(has_error(r, "h_total: measured 802 px, expected 800")) << all_errors(r);
}

TEST(ScanoutFault, WrongPorchNamedByMonitor) {
  // A source with a 20 px front porch and a 44 px back porch (same 800 total) into a
  // monitor set to VGA.
  const VideoTiming vga = *find_timing_preset("vga640x480@60");
  VideoTiming src = vga;
  src.h_front_porch = 20, src.h_back_porch = 44;
  const MonitorResult r = decode(src, vga, Dac(default_dac_config()), pattern(640, 480));
  EXPECT_TRUE(has_error(r, "h_front_porch: measured 20 px, expected 16")) << all_errors(r);
  EXPECT_TRUE(has_error(r, "h_back_porch: measured 44 px, expected 48")) << all_errors(r);
  EXPECT_FALSE(has_error(r, "h_total")) << all_errors(r);
}

TEST(ScanoutFault, FramebufferSmallerThanActiveRejectedByConfig) {
  Config cfg;
  cfg.set_from_string("display.timing", "vga640x480@60", "test");  // framebuffer stays 128x128
  try {
    video_timing_from_config(cfg);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("128x128 is smaller than the active area 640x480"), std::string::npos)
        << e.what();
  }
}

// A 640x480 framebuffer on the 128x128 panel would be cropped: an error naming both sizes
// and the preset of the framebuffer's size.
TEST(ScanoutFault, FramebufferLargerThanActiveRejectedByConfig) {
  Config cfg;
  cfg.set_from_string("display.width", "640", "test.toml:2");  // timing stays the 128x128 panel
  cfg.set_from_string("display.height", "480", "test.toml:3");
  try {
    video_timing_from_config(cfg);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("test.toml:2: framebuffer display.width x display.height = 640x480 is larger than the active "
                     "area 128x128 of display.timing = panel"), std::string::npos) << m;
    EXPECT_NE(m.find("vga640x480@60"), std::string::npos) << m;
  }
}

TEST(ScanoutFault, FramebufferSmallerThanActiveCaughtByMonitor) {
  const VideoTiming vga = *find_timing_preset("vga640x480@60");
  const MonitorResult r = decode(vga, vga, Dac(default_dac_config()), pattern(128, 128));
  EXPECT_TRUE(has_error(r, "h_active: measured 128 px, expected 640")) << all_errors(r);
  EXPECT_TRUE(has_error(r, "no pixel data")) << all_errors(r);
  EXPECT_EQ(r.no_data_pixels, 640u * 480 - 128 * 128);
}

TEST(ScanoutFault, UnderrunLinesCaughtByMonitor) {
  // Lines 0..99 of every frame come without data, as when the line buffer is empty.
  const VideoTiming t = *find_timing_preset("panel");
  const Dac dac(default_dac_config());
  const Framebuffer fb = pattern(128, 128);
  const Scanout so(t, dac, fb);
  Monitor mon(t, dac.config());
  for (int f = 0; f < 2; ++f)
    for (int v = 0; v < t.v_total; ++v)
      for (int h = 0; h < t.h_total; ++h) mon.push(so.sample(h, v, v >= 100));
  const MonitorResult r = mon.finish();
  EXPECT_TRUE(has_error(r, "underrun")) << all_errors(r);
  EXPECT_TRUE(has_error(r, "of lines 0..99")) << all_errors(r);
  EXPECT_EQ(r.no_data_pixels, 128u * 100);
}

TEST(ScanoutFault, InvertedSyncPolarityNamed) {
  const VideoTiming vga = *find_timing_preset("vga640x480@60");
  VideoTiming src = vga;
  src.h_sync_positive = true;
  const MonitorResult r = decode(src, vga, Dac(default_dac_config()), pattern(640, 480));
  EXPECT_TRUE(has_error(r, "hsync polarity: measured positive, expected negative")) << all_errors(r);
  EXPECT_EQ(rgb_mismatches(r.image, pattern(640, 480)), 0) << "polarity is detected, the picture still decodes";
}

TEST(ScanoutFault, MissingHsyncNamed) {
  const VideoTiming t = *find_timing_preset("panel");
  const Dac dac(default_dac_config());
  const Framebuffer fb = pattern(128, 128);
  Monitor mon(t, dac.config());
  Scanout(t, dac, fb).run(2, [&](VideoSample s) {
    s.hsync = true;  // stuck at the idle level
    mon.push(s);
  });
  const MonitorResult r = mon.finish();
  EXPECT_TRUE(has_error(r, "no hsync: the hsync wire stays high")) << all_errors(r);
  EXPECT_FALSE(r.locked);
}

TEST(ScanoutFault, SingleFrameIsNotEnoughToFrame) {
  const VideoTiming t = *find_timing_preset("panel");
  const MonitorResult r = decode(t, t, Dac(default_dac_config()), pattern(128, 128), 1);
  EXPECT_TRUE(has_error(r, "no complete frame")) << all_errors(r);
}

TEST(ScanoutConfig, CustomTimingFromKeys) {
  Config cfg;
  cfg.set_from_string("display.timing", "custom", "test");
  cfg.set_from_string("display.h_active_px", "100", "test");
  cfg.set_from_string("display.h_total_px", "132", "test");  // 100 + 8 + 16 + 8
  cfg.set_from_string("display.v_active_lines", "90", "test");
  cfg.set_from_string("display.v_total_lines", "98", "test");  // 90 + 2 + 2 + 4
  cfg.set_from_string("display.h_sync_polarity", "positive", "test");
  cfg.set_from_string("display.pixel_clock_mhz", "1.0", "test");
  cfg.set_from_string("display.width", "100", "test");  // the framebuffer is the active area
  cfg.set_from_string("display.height", "90", "test");
  const VideoTiming t = video_timing_from_config(cfg);
  EXPECT_EQ(t.h_active, 100);
  EXPECT_EQ(t.v_total, 98);
  EXPECT_TRUE(t.h_sync_positive);
  EXPECT_FALSE(t.v_sync_positive);
  EXPECT_NEAR(t.line_rate_hz(), 1e6 / 132, 1e-9);
  // The scan-out model given a larger framebuffer reads its top-left corner (a config
  // refuses that pairing: FramebufferLargerThanActiveRejectedByConfig).
  const Dac dac(default_dac_config());
  const Framebuffer fb = pattern(128, 128);
  const MonitorResult r = decode(t, t, dac, fb);
  EXPECT_TRUE(r.ok()) << all_errors(r);
  EXPECT_EQ(r.image.pixel(99, 89)[0], fb.pixel(99, 89)[0]);
}

TEST(ScanoutConfig, ExplicitKeyBesidePresetRejected) {
  Config cfg;
  cfg.set_from_string("display.h_sync_px", "20", "test.toml:3");
  try {
    video_timing_from_config(cfg);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("display.h_sync_px is set"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim
