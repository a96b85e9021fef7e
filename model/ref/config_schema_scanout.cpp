// SPDX-License-Identifier: Apache-2.0
// Keys of video timing (display.timing and the explicit custom-timing keys), the video
// DAC (dac.*) and the scan-out stage (scanout.*). The preset values live in one table
// (video_timing.cpp); the custom keys default to the `panel` preset's values from it.
#include "config.h"
#include "video_timing.h"

namespace rastsim {

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
    add({key, T::Int, int64_t{def}, "px", lo, 16384, {}, std::string("Custom timing: ") + what});
  };
  auto lines = [&](const char* key, int def, double lo, const char* what) {
    add({key, T::Int, int64_t{def}, "lines", lo, 16384, {}, std::string("Custom timing: ") + what});
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
