// SPDX-License-Identifier: Apache-2.0
// Video timing presets and the config -> VideoTiming mapping.
#include "config/video_timing.h"

#include <cstdio>

namespace rastsim {

namespace {

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

// The scan-out shows the framebuffer pixel for pixel: display.width x display.height must
// be the active area. Smaller leaves part of the screen without pixels; larger would show
// only its top-left corner, a crop nobody asked for. Either is a config error naming both
// sizes and, when one exists, the preset of the framebuffer's size.
void check_framebuffer_is_active_area(const Config& cfg, const VideoTiming& t) {
  const int64_t fw = cfg.get_int("display.width"), fh = cfg.get_int("display.height");
  if (fw == t.h_active && fh == t.v_active) return;
  const std::string where = cfg.origin(cfg.origin("display.width") != "default" ? "display.width" : "display.timing");
  const std::string fb = "framebuffer display.width x display.height = " + std::to_string(fw) + "x" + std::to_string(fh);
  const std::string mode = "the active area " + std::to_string(t.h_active) + "x" + std::to_string(t.v_active) +
                           " of display.timing = " + cfg.get_string("display.timing");
  if (fw < t.h_active || fh < t.v_active)
    throw ConfigError(where + ": " + fb + " is smaller than " + mode +
                      ": the scan-out would have no pixels for part of the screen");
  std::string fix = "a custom timing (display.timing = \"custom\") of that size";
  for (const auto& p : timing_presets())
    if (p.h_active == fw && p.v_active == fh) fix = "display.timing = \"" + p.name + "\"";
  throw ConfigError(where + ": " + fb + " is larger than " + mode + ": the scan-out would show only its top-left " +
                    std::to_string(t.h_active) + "x" + std::to_string(t.v_active) + "; use " + fix);
}

}  // namespace

std::vector<std::string> VideoTiming::problems() const {
  std::vector<std::string> out;
  for (auto& p : {axis_problem("horizontal", "px", h_active, h_front_porch, h_sync, h_back_porch, h_total),
                  axis_problem("vertical", "lines", v_active, v_front_porch, v_sync, v_back_porch, v_total)})
    if (!p.empty()) out.push_back(p);
  if (!(pixel_clock_hz > 0)) out.push_back("pixel clock must be positive");
  return out;
}

VideoTiming video_timing_from_config(const Config& cfg) {
  const std::string& name = cfg.get_string("display.timing");
  VideoTiming t;
  if (const VideoTiming* p = find_timing_preset(name)) {
    t = *p;
    // A key set to its default is no conflict: `config --toml` writes every key, so its
    // text (and a stats JSON's config_toml) reads back with them all set.
    for (const char* k : kExplicitKeys)
      if (cfg.origin(k) != "default" && !(cfg.get(k) == find_param(k)->default_value))
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
  check_framebuffer_is_active_area(cfg, t);
  return t;
}

}  // namespace rastsim
