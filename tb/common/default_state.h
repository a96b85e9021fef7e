// SPDX-License-Identifier: Apache-2.0
// The RasterState of configs/default.toml, for tests that render shipped scenes with the
// shipped defaults.
#pragma once

#include <string>

#include "config/raster_state_config.h"

namespace rastsim::testing_common {

inline RasterState default_state() {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml");
  return raster_state_from_config(cfg);
}

}  // namespace rastsim::testing_common
