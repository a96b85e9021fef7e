// SPDX-License-Identifier: Apache-2.0
// One co-simulation run's testbench before any model is clocked: the checks a config
// must pass to run on the RTL, the parameters it needs, and the stimulus, expected
// fragments and reference image (TbSetup, testbench.h). Shared by run_cosim (the
// shipped models, in the calling process) and the on-demand runner (rtl_runner_main.cpp,
// a process of its own, built into the cache by rtl_cache.cpp), so both run the same
// testbench. Internal to model/rtlsim; callers use cosim.h.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "rtlsim/cosim.h"

namespace rastsim::rtlsim {

struct TbSetup;  // testbench.h

// Throws, naming the config's key, when the RTL cannot run `cfg` (raster.traversal,
// interp.method, raster.aa_mode, the tile size); else the parameters a model must be
// compatible with (rtl_params_compatible): the config's, with the tile size and sample
// count as run-time values (each up to a model's maximum).
RtlParams cosim_wanted_params(const ArchParams& arch, const CosimOptions& opts);

// The testbench of one run of `scene` on a model built with `model`; fills r's counts
// known before the run (fragments_expected, triangles, markers, commands_2d,
// resolve_cycles).
void cosim_setup(const Scene& scene, const ArchParams& arch, const CosimOptions& opts, const RtlParams& model, TbSetup& s,
                 CosimResult& r);

// What the parent sends the on-demand runner (a JSON file): every config value with its
// origin (so the runner's messages name the same file:line), the scene's file and
// command count (the runner reads the file again), the options.
nlohmann::json runner_request(const Scene& scene, const ArchParams& arch, const CosimOptions& opts);
struct RunnerRequest {
  Config config;
  std::string scene;
  size_t scene_commands = 0;
  CosimOptions options;
};
RunnerRequest read_runner_request(const nlohmann::json& j);

}  // namespace rastsim::rtlsim
