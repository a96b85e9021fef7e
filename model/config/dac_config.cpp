// SPDX-License-Identifier: Apache-2.0
#include "config/dac_config.h"

namespace rastsim {

DacConfig dac_config_from_config(const Config& cfg) {
  DacConfig c;
  c.bits = static_cast<int>(cfg.get_int("dac.bits"));
  c.full_scale_volts = cfg.get_float("dac.full_scale_volts");
  c.inl_lsb = cfg.get_float("dac.inl_lsb");
  c.dnl_lsb = cfg.get_float("dac.dnl_lsb");
  c.seed = static_cast<uint64_t>(cfg.get_int("dac.seed"));
  c.lut = cfg.get_string("dac.lut") == "gamma" ? DacLut::Gamma : DacLut::Linear;
  c.gamma = cfg.get_float("dac.gamma");
  return c;
}

}  // namespace rastsim
