// SPDX-License-Identifier: Apache-2.0
// RTL scan-out (Verilator) against the reference scan-out, signal by signal, for two
// whole frames, for the panel and VGA configs; the RTL's output decoded by the virtual
// monitor. The RTL is scanout_top's Latency pixel clocks behind the reference
// (rtl/scanout_top.sv, a public localparam).
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "Vscanout_panel.h"
#include "Vscanout_panel__Syms.h"
#include "Vscanout_vga.h"
#include "Vscanout_vga__Syms.h"
#include "scanout_test_util.h"

namespace rastsim {
namespace {

// scanout_top's public localparam Latency, from the class Verilator generated for the
// cosim top's instance u_scanout (its name depends on the parameters; the member's does not).
template <class Syms>
constexpr int kLatencyOf = decltype(Syms::TOP__scanout_cosim_top__u_scanout)::Latency;
constexpr int kLatency = kLatencyOf<Vscanout_panel__Syms>;
static_assert(kLatencyOf<Vscanout_vga__Syms> == kLatency);

struct RtlRun {
  long long compared = 0, mismatches = 0;
  std::string first_mismatch;
  MonitorResult decoded;
};

// Runs `frames` frames of the RTL with `cfg_name`'s config; `has_data(v)` says whether
// the framebuffer delivers line v (false: fb_rvalid_i low, an underrun).
template <class V>
RtlRun run_rtl(const char* cfg_name, int frames, const std::function<bool(int)>& has_data = {}) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SCANOUT_CONFIGS) + "/" + cfg_name + ".toml");
  cfg.validate();
  const VideoTiming t = video_timing_from_config(cfg);
  const Dac dac(dac_config_from_config(cfg));
  const Framebuffer fb = scanout_test::pattern(int(cfg.get_int("display.width")), int(cfg.get_int("display.height")));
  const Scanout ref(t, dac, fb);
  Monitor mon(t, dac.config());

  auto top = std::make_unique<V>();
  top->rst_ni = 0;
  top->clk_i = 0;
  top->fb_rvalid_i = 0;
  top->eval();
  for (int v = 0; v < 256; ++v) {  // load the palettes while in reset
    top->pal_we_i = 7, top->pal_waddr_i = v, top->pal_wdata_i = dac.code(uint8_t(v));
    top->clk_i = 1, top->eval();
    top->clk_i = 0, top->eval();
  }
  top->pal_we_i = 0;
  top->rst_ni = 1;
  top->eval();

  RtlRun out;
  const long long n = static_cast<long long>(frames) * t.pixels_per_frame();
  for (long long j = 0; j < n + kLatency; ++j) {
    if (j >= kLatency) {  // the state now shows position j - kLatency
      const long long p = j - kLatency;
      const int h = int(p % t.h_total), v = int(p / t.h_total % t.v_total);
      const VideoSample want = ref.sample(h, v, !has_data || has_data(v));
      VideoSample got;
      got.hsync = top->hsync_o, got.vsync = top->vsync_o, got.blank = top->blank_o;
      got.code = {uint16_t(top->dac_r_o), uint16_t(top->dac_g_o), uint16_t(top->dac_b_o)};
      for (int c = 0; c < 3; ++c) got.volts[c] = static_cast<float>(dac.volts(c, got.code[c]));
      if (got.blank) got.volts = {0, 0, 0};
      mon.push(got);
      ++out.compared;
      if (!(got == want) && out.mismatches++ == 0) {
        const char* what = got.hsync != want.hsync ? "hsync" : got.vsync != want.vsync ? "vsync"
                           : got.blank != want.blank ? "blank" : "DAC codes";
        out.first_mismatch = std::string(what) + " at frame " + std::to_string(p / t.pixels_per_frame()) +
                             " line " + std::to_string(v) + " pixel " + std::to_string(h) + ": RTL " +
                             std::to_string(got.code[0]) + "/" + std::to_string(got.blank) + ", reference " +
                             std::to_string(want.code[0]) + "/" + std::to_string(want.blank);
      }
    }
    const bool rd = top->fb_rd_o;
    const uint32_t addr = top->fb_addr_o;
    const int line = int(j / t.h_total % t.v_total);
    top->clk_i = 1, top->eval();
    // Synchronous RAM: the data asked for appears after the edge.
    if (rd) {
      const uint8_t* px = fb.pixel(int(addr % uint32_t(fb.width)), int(addr / uint32_t(fb.width)));
      top->fb_rdata_i = uint32_t(px[0]) << 16 | uint32_t(px[1]) << 8 | px[2];
    }
    top->fb_rvalid_i = rd && (!has_data || has_data(line));
    top->clk_i = 0, top->eval();
  }
  top->final();
  out.decoded = mon.finish();
  return out;
}

TEST(ScanoutRtl, PanelWholeFramesMatchReference) {
  const RtlRun r = run_rtl<Vscanout_panel>("panel", 2);
  EXPECT_EQ(r.compared, 2LL * 160 * 136);
  EXPECT_EQ(r.mismatches, 0) << r.first_mismatch;
  EXPECT_TRUE(r.decoded.ok());
  EXPECT_EQ(scanout_test::rgb_mismatches(r.decoded.image, scanout_test::pattern(128, 128)), 0);
  EXPECT_EQ(r.decoded.measured.h_total, 160);
  EXPECT_EQ(r.decoded.measured.v_total, 136);
}

TEST(ScanoutRtl, VgaWholeFramesMatchReference) {
  const RtlRun r = run_rtl<Vscanout_vga>("vga", 2);
  EXPECT_EQ(r.compared, 2LL * 800 * 525);
  EXPECT_EQ(r.mismatches, 0) << r.first_mismatch;
  ASSERT_TRUE(r.decoded.ok()) << r.decoded.errors.front();
  EXPECT_EQ(scanout_test::rgb_mismatches(r.decoded.image, scanout_test::pattern(640, 480)), 0);
  // Published VGA numbers: 800x525 total, 96 px hsync, 2 lines vsync, 16/48 px porches.
  EXPECT_EQ(r.decoded.measured.h_total, 800);
  EXPECT_EQ(r.decoded.measured.v_total, 525);
  EXPECT_EQ(r.decoded.measured.h_sync, 96);
  EXPECT_EQ(r.decoded.measured.v_sync, 2);
  EXPECT_EQ(r.decoded.measured.h_front_porch, 16);
  EXPECT_EQ(r.decoded.measured.h_back_porch, 48);
  EXPECT_EQ(r.decoded.measured.v_back_porch, 33);
}

TEST(ScanoutRtl, PanelUnderrunBlanksLinesLikeReference) {
  // The framebuffer does not deliver lines 20..29: the RTL must blank exactly those
  // pixels (the reference with has_data false) and the monitor must call it an underrun.
  const RtlRun r = run_rtl<Vscanout_panel>("panel", 2, [](int v) { return v < 20 || v >= 30; });
  EXPECT_EQ(r.mismatches, 0) << r.first_mismatch;
  ASSERT_FALSE(r.decoded.ok());
  EXPECT_NE(r.decoded.errors.back().find("underrun"), std::string::npos) << r.decoded.errors.back();
  EXPECT_EQ(r.decoded.no_data_pixels, 128u * 10);
}

}  // namespace
}  // namespace rastsim
