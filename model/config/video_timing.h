// SPDX-License-Identifier: Apache-2.0
// Video timing: the raster-scan geometry of one display mode (active area, porches,
// sync widths and polarities, pixel clock), from a named preset or explicit keys.
//
// Counter convention (shared by the reference scan-out, the SystemC model and the RTL):
// a line is [active | front porch | sync | back porch], hcount 0 .. h_total-1 with the
// first active pixel at hcount 0; a frame is the same in lines, vcount 0 .. v_total-1.
// vsync changes at hcount 0 of a line. All widths are in pixel clocks (horizontal) or
// lines (vertical).
#pragma once

#include <string>
#include <vector>

#include "config/config.h"

namespace rastsim {

struct VideoTiming {
  std::string name;  // preset name or "custom"
  int h_active = 0, h_front_porch = 0, h_sync = 0, h_back_porch = 0, h_total = 0;  // px
  int v_active = 0, v_front_porch = 0, v_sync = 0, v_back_porch = 0, v_total = 0;  // lines
  bool h_sync_positive = false;  // true: hsync is high during the pulse
  bool v_sync_positive = false;
  double pixel_clock_hz = 0;

  // Derived rates. For VGA: 25.175 MHz / 800 = 31.469 kHz, / 525 = 59.94 Hz.
  double line_rate_hz() const { return pixel_clock_hz / h_total; }
  double frame_rate_hz() const { return line_rate_hz() / v_total; }
  long long pixels_per_frame() const { return static_cast<long long>(h_total) * v_total; }
  // Empty when active + porches + sync == total on both axes and every width is
  // positive; otherwise one message per broken axis (names the values).
  std::vector<std::string> problems() const;
  bool operator==(const VideoTiming&) const = default;
};

// The presets `display.timing` names (not "custom"), in declaration order; the table
// sits beside the keys in config_schema_scanout.cpp.
const std::vector<VideoTiming>& timing_presets();
// nullptr when there is no preset of that name.
const VideoTiming* find_timing_preset(const std::string& name);

// The timing the config selects: the preset, or the explicit display.h_* / display.v_*
// keys when display.timing = custom. Throws ConfigError naming the keys when the
// porches do not add up to the total, when explicit keys are set beside a preset, or
// when the framebuffer (display.width x display.height) is not the active area (both named).
VideoTiming video_timing_from_config(const Config& cfg);

// One line a preset: "vga640x480@60: 640x480, 800x525 total, 25.175 MHz -> 31.469 kHz,
// 59.94 Hz" (for `rastsim config --doc` and the scan-out command).
std::string describe_timing(const VideoTiming& t);

}  // namespace rastsim
