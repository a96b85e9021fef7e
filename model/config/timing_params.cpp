// SPDX-License-Identifier: Apache-2.0
#include "config/timing_params.h"

namespace rastsim {

TimingParams TimingParams::from_config(const Config& cfg) {
  TimingParams p;
  auto u = [&](const char* key) { return static_cast<uint64_t>(cfg.get_int(key)); };
  auto depth = [&](const char* key) { return static_cast<int>(cfg.get_int(key)); };
  p.core_mhz = cfg.get_float("clock.core_mhz");
  p.fetch_cycles_per_command = u("fetch.cycles_per_command");
  p.fetch_vertices_per_cycle = u("fetch.vertices_per_cycle");
  p.assembly_cycles_per_triangle = u("assembly.cycles_per_triangle");
  p.setup_interval = u("setup.interval_cycles");
  p.setup_latency = u("setup.latency_cycles");
  p.coarse_tiles_per_cycle = u("coarse.tiles_per_cycle");
  p.fine_samples_per_cycle = u("fine.samples_per_cycle");
  p.fine_accepted_tile_cycles = u("fine.accepted_tile_cycles");
  p.interp_fragments_per_cycle = u("interp.fragments_per_cycle");
  p.interp_latency = u("interp.latency_cycles");
  p.rop_pixels_per_cycle = u("rop.pixels_per_cycle");
  p.rop_clear_pixels_per_cycle = u("rop.clear_pixels_per_cycle");
  p.fifo_command = depth("fifo.command_depth");
  p.fifo_triangle = depth("fifo.triangle_depth");
  p.fifo_setup = depth("fifo.setup_depth");
  p.fifo_tile = depth("fifo.tile_depth");
  p.fifo_pixel = depth("fifo.pixel_depth");
  p.fifo_fragment = depth("fifo.fragment_depth");
  if (p.setup_latency < p.setup_interval)
    throw ConfigError(cfg.origin("setup.latency_cycles") + ": setup.latency_cycles = " +
                      std::to_string(p.setup_latency) + " is less than setup.interval_cycles = " +
                      std::to_string(p.setup_interval) + " (" + cfg.origin("setup.interval_cycles") +
                      "); a pipelined stage cannot finish a triangle before accepting the next");
  return p;
}

}  // namespace rastsim
