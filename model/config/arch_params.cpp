// SPDX-License-Identifier: Apache-2.0
#include "config/arch_params.h"

#include "config/memory_config.h"
#include "config/raster_state_config.h"

namespace rastsim {

ArchParams ArchParams::resolve(const Config& cfg) {
  ArchParams a;
  a.config = cfg;
  a.raster = raster_state_from_config(cfg);
  a.timing = TimingParams::from_config(cfg);
  a.dram = dram_params_from_config(cfg);
  a.rtl_max_samples = static_cast<int>(cfg.get_int("raster.max_samples"));
  a.placement = obj_placement_from_config(cfg);
  a.memory = memory_params_from_config(cfg);
  return a;
}

DisplayParams DisplayParams::resolve(const Config& cfg) {
  DisplayParams d;
  d.video = video_timing_from_config(cfg);
  d.dac = dac_config_from_config(cfg);
  d.single_buffered = cfg.get_string("scanout.buffering") == "single";
  d.line_buffer_lines = static_cast<int>(cfg.get_int("scanout.line_buffer_lines"));
  d.fetch_px_per_cycle = static_cast<int>(cfg.get_int("scanout.fetch_px_per_cycle"));
  return d;
}

}  // namespace rastsim
