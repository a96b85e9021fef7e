// SPDX-License-Identifier: Apache-2.0
// DacConfig: the video DAC's dac.* keys as typed parameters (the DAC model is
// model/display/dac.h).
#pragma once

#include <cstdint>

#include "config/config.h"

namespace rastsim {

enum class DacLut { Linear, Gamma };

// The dac.* keys; every value comes from dac_config_from_config (no defaults here).
struct DacConfig {
  int bits = 0;
  double full_scale_volts = 0;   // V
  double inl_lsb = 0, dnl_lsb = 0;
  uint64_t seed = 0;
  DacLut lut = DacLut::Linear;
  double gamma = 0;
};

DacConfig dac_config_from_config(const Config& cfg);

}  // namespace rastsim
