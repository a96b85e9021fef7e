// SPDX-License-Identifier: Apache-2.0
// The video-timing stats keys shared by `rastsim scanout` and `rastsim monitor`
// (defined in cmd_scanout.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include "config/video_timing.h"
#include "display/monitor.h"

namespace rastsim::app {

// A timing's fields (porches, sync widths and polarities, totals, pixel clock, line and
// frame rates) as JSON keys.
nlohmann::json timing_json(const VideoTiming& t);

// The monitor's measured timing and verdict (frames decoded, no-data pixels, errors).
nlohmann::json measured_json(const MonitorResult& r);

}  // namespace rastsim::app
