// SPDX-License-Identifier: Apache-2.0
// A run's configuration resolved once, at the command's entry, into typed and validated
// parameters; below the command layer (app/) the model reads these, never the raw
// Config (docs/architecture.md, "Configuration flows one way").
//
// ArchParams is what every run of the raster engine needs: the raster state, the timing
// of every stage, the RTL's build-time sample maximum and the OBJ placement. The memory
// and texture parameters join it here. DisplayParams is the scan-out end (video timing,
// DAC, scan-out buffering), resolved only by the commands that scan out: a config that
// only renders need not hold a valid video timing.
#pragma once

#include "config/config.h"
#include "config/dac_config.h"
#include "config/dram_config.h"
#include "config/obj_placement.h"
#include "config/timing_params.h"
#include "config/video_timing.h"
#include "ref/memory/memory_params.h"
#include "ref/raster_state.h"

namespace rastsim {

struct ArchParams {
  // The validated config these were resolved from: its name and text for provenance
  // (stats, the RTL model cache key) and for child processes handed the same run.
  Config config;
  RasterState raster;      // raster.*, display size, formats (raster_state_config.h)
  TimingParams timing;     // every stage's cost terms and FIFO depths (timing_params.h)
  int rtl_max_samples = 0; // raster.max_samples: the RTL's build-time sample maximum
  ObjPlacement placement;  // scene.obj_* and the display size (obj_placement.h)
  DramParams dram;         // memory.preset, dram.* and the core clock (dram_config.h)
  MemoryParams memory;     // memory.* and the ROP's caches (memory_config.h)

  // Reads and cross-checks every key above; throws ConfigError naming the key.
  static ArchParams resolve(const Config& cfg);
};

struct DisplayParams {
  VideoTiming video;             // display.timing and its keys (video_timing.h)
  DacConfig dac;                 // dac.* (dac_config.h)
  bool single_buffered = false;  // scanout.buffering == "single"
  int line_buffer_lines = 0;     // scanout.line_buffer_lines
  int fetch_px_per_cycle = 0;    // scanout.fetch_px_per_cycle

  // Throws ConfigError naming the key when the video timing does not fit the display.
  static DisplayParams resolve(const Config& cfg);
};

}  // namespace rastsim
