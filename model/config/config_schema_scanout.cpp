// SPDX-License-Identifier: Apache-2.0
// Keys of video timing (display.timing and the explicit custom-timing keys), the video
// DAC (dac.*) and the scan-out stage (scanout.*). The preset values live in one table
// below, beside the keys; the custom keys default to the `panel` preset's values.
// (Self-contained with config.cpp: tools that build only the config sources link it.)
#include <cstdio>

#include "config/config_schema.h"
#include "config/video_timing.h"
#include "ref/framebuffer.h"

namespace rastsim {

namespace {

VideoTiming make(const char* name, int ha, int hfp, int hs, int hbp, int va, int vfp, int vs, int vbp,
                 bool hpos, bool vpos, double pclk_hz) {
  VideoTiming t;
  t.name = name;
  t.h_active = ha, t.h_front_porch = hfp, t.h_sync = hs, t.h_back_porch = hbp;
  t.h_total = ha + hfp + hs + hbp;
  t.v_active = va, t.v_front_porch = vfp, t.v_sync = vs, t.v_back_porch = vbp;
  t.v_total = va + vfp + vs + vbp;
  t.h_sync_positive = hpos, t.v_sync_positive = vpos;
  t.pixel_clock_hz = pclk_hz;
  return t;
}

std::vector<VideoTiming> make_presets() {
  return {
      // A small panel matching the default 128x128 viewport: short porches, 160x136
      // total, pixel clock chosen for exactly 60 Hz (160 * 136 * 60 = 1.3056 MHz).
      make("panel", 128, 8, 16, 8, 128, 2, 2, 4, false, false, 1.3056e6),
      // VESA/IBM VGA 640x480 "@60": 25.175 MHz, 800x525, negative syncs.
      make("vga640x480@60", 640, 16, 96, 48, 480, 10, 2, 33, false, false, 25.175e6),
      // CEA-861 1280x720p60 (VIC 4): 74.25 MHz, 1650x750, positive syncs.
      make("720p60", 1280, 110, 40, 220, 720, 5, 5, 20, true, true, 74.25e6),
      // CEA-861 1920x1080p60 (VIC 16): 148.5 MHz, 2200x1125, positive syncs.
      make("1080p60", 1920, 88, 44, 148, 1080, 4, 5, 36, true, true, 148.5e6),
  };
}

}  // namespace

const std::vector<VideoTiming>& timing_presets() {
  static const std::vector<VideoTiming> presets = make_presets();
  return presets;
}

const VideoTiming* find_timing_preset(const std::string& name) {
  for (const auto& p : timing_presets())
    if (p.name == name) return &p;
  return nullptr;
}

std::string describe_timing(const VideoTiming& t) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%s: %dx%d active, %dx%d total, porches h %d/%d/%d v %d/%d/%d, %s/%s syncs, %.6g MHz -> "
                "line %.3f kHz, frame %.2f Hz",
                t.name.c_str(), t.h_active, t.v_active, t.h_total, t.v_total, t.h_front_porch, t.h_sync,
                t.h_back_porch, t.v_front_porch, t.v_sync, t.v_back_porch, t.h_sync_positive ? "+" : "-",
                t.v_sync_positive ? "+" : "-", t.pixel_clock_hz / 1e6, t.line_rate_hz() / 1e3,
                t.frame_rate_hz());
  return buf;
}


void add_scanout_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  auto add = [&](ParamDef d) { s.push_back(std::move(d)); };
  const VideoTiming& panel = *find_timing_preset("panel");

  // ---- display: video timing (the active area; display.width/height is the framebuffer) ----
  std::vector<std::string> names;
  std::string doc = "Video timing: a preset, or custom (then the display.h_*/display.v_* keys apply). Presets:";
  for (const auto& p : timing_presets()) {
    names.push_back(p.name);
    doc += "\n        " + describe_timing(p);
  }
  names.push_back("custom");
  add({"display.timing", T::Enum, std::string("panel"), "", 1, 0, names, doc});

  auto px = [&](const char* key, int def, double lo, const char* what) {
    add({key, T::Int, int64_t{def}, "px", lo, kMaxImageExtent, {}, std::string("Custom timing: ") + what});
  };
  auto lines = [&](const char* key, int def, double lo, const char* what) {
    add({key, T::Int, int64_t{def}, "lines", lo, kMaxImageExtent, {}, std::string("Custom timing: ") + what});
  };
  px("display.h_active_px", panel.h_active, 1, "active pixels a line");
  px("display.h_front_porch_px", panel.h_front_porch, 0, "blanking from the last active pixel to hsync");
  px("display.h_sync_px", panel.h_sync, 1, "hsync pulse width");
  px("display.h_back_porch_px", panel.h_back_porch, 0, "blanking from the end of hsync to the first active pixel");
  px("display.h_total_px", panel.h_total, 4, "line period; must equal active + porches + sync");
  lines("display.v_active_lines", panel.v_active, 1, "active lines a frame");
  lines("display.v_front_porch_lines", panel.v_front_porch, 0, "blank lines from the last active line to vsync");
  lines("display.v_sync_lines", panel.v_sync, 1, "vsync pulse width");
  lines("display.v_back_porch_lines", panel.v_back_porch, 0, "blank lines from the end of vsync to the first active line");
  lines("display.v_total_lines", panel.v_total, 4, "frame period; must equal active + porches + sync");
  add({"display.h_sync_polarity", T::Enum, std::string(panel.h_sync_positive ? "positive" : "negative"), "", 1, 0,
       {"negative", "positive"}, "Custom timing: level of hsync during the pulse (negative: low)"});
  add({"display.v_sync_polarity", T::Enum, std::string(panel.v_sync_positive ? "positive" : "negative"), "", 1, 0,
       {"negative", "positive"}, "Custom timing: level of vsync during the pulse (negative: low)"});
  add({"display.pixel_clock_mhz", T::Float, panel.pixel_clock_hz / 1e6, "MHz", 0.001, 1000, {},
       "Custom timing: pixel clock; line rate = clock / h_total, frame rate = line rate / v_total"});

  // ---- dac: the video DAC (RAMDAC: palette lookup, then one DAC a channel) ----
  add({"dac.bits", T::Int, int64_t{8}, "bits", 1, 10, {},
       "DAC resolution a channel; framebuffer bytes map to codes through the lookup table"});
  add({"dac.full_scale_volts", T::Float, 0.7, "V", 0.1, 2.0, {},
       "Level of the largest code into a doubly terminated 75 ohm load (blank and code 0 are 0 V)"});
  add({"dac.inl_lsb", T::Float, 0.0, "LSB", 0, 64, {},
       "Largest integral nonlinearity (endpoint fit) of the seeded mismatch model; 0 = ideal"});
  add({"dac.dnl_lsb", T::Float, 0.0, "LSB", 0, 4, {},
       "Largest differential nonlinearity (step error) of the mismatch model; >= 1 allows non-monotonic steps"});
  add({"dac.seed", T::Int, int64_t{1}, "", 0, 2147483647.0, {},
       "Seed of the mismatch model (each channel draws its own curve from it)"});
  add({"dac.lut", T::Enum, std::string("linear"), "", 1, 0, {"linear", "gamma"},
       "Palette RAM contents: linear (code = round(v * (2^bits-1) / 255)) or a gamma ramp"});
  add({"dac.gamma", T::Float, 2.2, "", 0.1, 5, {},
       "With dac.lut = gamma: code = round((v/255)^(1/gamma) * (2^bits-1))"});

  // ---- scanout: the timed stage (model/sc) ----
  add({"scanout.buffering", T::Enum, std::string("double"), "", 1, 0, {"double", "single"},
       "double: raster draws the next frame while this one is shown (deadline: one frame); single: raster "
       "draws into the shown buffer from the start of vertical blanking (deadline: the blanking interval)"});
  add({"scanout.line_buffer_lines", T::Int, int64_t{2}, "lines", 1, 64, {},
       "Line buffer (FIFO) depth between the framebuffer fetch and the pixel-clock side"});
  add({"scanout.fetch_px_per_cycle", T::Int, int64_t{4}, "px/cycle", 1, 64, {},
       "Framebuffer read bandwidth of the line fetch, in pixels a core clock cycle"});
}

}  // namespace rastsim
