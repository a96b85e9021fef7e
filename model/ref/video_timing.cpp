// SPDX-License-Identifier: Apache-2.0
// Video timing presets and the config -> VideoTiming mapping.
#include "video_timing.h"

#include <cstdio>

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

std::string axis_problem(const char* axis, const char* unit, int active, int fp, int sync, int bp, int total) {
  const int sum = active + fp + sync + bp;
  char buf[256];
  if (active < 1 || sync < 1 || fp < 0 || bp < 0) {
    std::snprintf(buf, sizeof buf, "%s: active %d and sync %d must be >= 1, porches %d and %d >= 0", axis,
                  active, sync, fp, bp);
    return buf;
  }
  if (sum == total) return {};
  std::snprintf(buf, sizeof buf,
                "%s: active %d + front porch %d + sync %d + back porch %d = %d %s, but the total is %d %s",
                axis, active, fp, sync, bp, sum, unit, total, unit);
  return buf;
}

// The explicit keys, in the order the custom timing reads them.
const char* const kExplicitKeys[] = {
    "display.h_active_px",      "display.h_front_porch_px",   "display.h_sync_px",
    "display.h_back_porch_px",  "display.h_total_px",         "display.v_active_lines",
    "display.v_front_porch_lines", "display.v_sync_lines",    "display.v_back_porch_lines",
    "display.v_total_lines",    "display.h_sync_polarity",    "display.v_sync_polarity",
    "display.pixel_clock_mhz",
};

}  // namespace

std::vector<std::string> VideoTiming::problems() const {
  std::vector<std::string> out;
  for (auto& p : {axis_problem("horizontal", "px", h_active, h_front_porch, h_sync, h_back_porch, h_total),
                  axis_problem("vertical", "lines", v_active, v_front_porch, v_sync, v_back_porch, v_total)})
    if (!p.empty()) out.push_back(p);
  if (!(pixel_clock_hz > 0)) out.push_back("pixel clock must be positive");
  return out;
}

const std::vector<VideoTiming>& timing_presets() {
  static const std::vector<VideoTiming> presets = make_presets();
  return presets;
}

const VideoTiming* find_timing_preset(const std::string& name) {
  for (const auto& p : timing_presets())
    if (p.name == name) return &p;
  return nullptr;
}

VideoTiming video_timing_from_config(const Config& cfg) {
  const std::string& name = cfg.get_string("display.timing");
  VideoTiming t;
  if (const VideoTiming* p = find_timing_preset(name)) {
    t = *p;
    for (const char* k : kExplicitKeys)
      if (cfg.origin(k) != "default")
        throw ConfigError(cfg.origin(k) + ": " + k + " is set, but display.timing = " + name + " (" +
                          cfg.origin("display.timing") +
                          ") is a preset; set display.timing = \"custom\" to use the explicit keys");
  } else {
    auto i = [&](const char* k) { return static_cast<int>(cfg.get_int(k)); };
    t.name = "custom";
    t.h_active = i("display.h_active_px"), t.h_front_porch = i("display.h_front_porch_px");
    t.h_sync = i("display.h_sync_px"), t.h_back_porch = i("display.h_back_porch_px");
    t.h_total = i("display.h_total_px");
    t.v_active = i("display.v_active_lines"), t.v_front_porch = i("display.v_front_porch_lines");
    t.v_sync = i("display.v_sync_lines"), t.v_back_porch = i("display.v_back_porch_lines");
    t.v_total = i("display.v_total_lines");
    t.h_sync_positive = cfg.get_string("display.h_sync_polarity") == "positive";
    t.v_sync_positive = cfg.get_string("display.v_sync_polarity") == "positive";
    t.pixel_clock_hz = cfg.get_float("display.pixel_clock_mhz") * 1e6;
    const auto probs = t.problems();
    if (!probs.empty())
      throw ConfigError("display.timing = custom: " + probs.front() +
                        " (keys display.h_* / display.v_*; the porches and sync must add up to the total)");
  }
  const int64_t fw = cfg.get_int("display.width"), fh = cfg.get_int("display.height");
  if (fw < t.h_active || fh < t.v_active)
    throw ConfigError(cfg.origin(cfg.origin("display.width") != "default" ? "display.width" : "display.timing") +
                      ": framebuffer display.width x display.height = " +
                      std::to_string(fw) + "x" + std::to_string(fh) + " is smaller than the active area " +
                      std::to_string(t.h_active) + "x" + std::to_string(t.v_active) + " of display.timing = " +
                      name + ": the scan-out would have no pixels for part of the screen");
  return t;
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

}  // namespace rastsim
