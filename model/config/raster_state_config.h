// SPDX-License-Identifier: Apache-2.0
// RasterState from the config (config -> typed parameters, one way).
#pragma once

#include "config/config.h"
#include "ref/raster_state.h"

namespace rastsim {

// Builds the architecture part from a validated config; viewport = display size.
RasterState raster_state_from_config(const Config& cfg);

// A raster.depth_func name ("less", ...) as the state's DepthFunc; throws ConfigError on
// any other name (a validated config holds only these).
DepthFunc depth_func_from_name(const std::string& name);

}  // namespace rastsim
