// SPDX-License-Identifier: Apache-2.0
// On-demand RTL models: a config no shipped model fits (cosim.h, prepare_rtl_model) is
// verilated once into a cache and run as a child process (docs/rtl.md, "Any config
// through the RTL").
//
// - Cache: rastsim_cache_dir("rtl") = $RASTSIM_CACHE/rtl, else
//   $XDG_CACHE_HOME/rastsim/rtl, else ~/.cache/rastsim/rtl (`rastsim area` keeps its
//   entries beside it, in .../area). One directory an entry, named by its key:
//   <key>/rast_runner (the model and testbench, rtl_runner_main.cpp), manifest.json (the
//   parameters, what it was built for, build seconds), build.log, rast_params.vh.
// - Key: FNV-1a 64 of the parameter set (rtl_params_values) and of everything else an
//   entry is built from (rtl_build_inputs): the RTL and project text compiled into this
//   binary (rtl_sources.h), the compiler, Verilator, the build type, and the content of
//   the static libraries the runner links from rastsim's build tree. Another binary with
//   the same inputs shares the entries.
// - Lookup: the key's entry, else any entry with the same inputs whose parameters are
//   compatible (rtl_params_compatible: the tile size and sample count as run-time values
//   up to the built maxima), else a build.
// - Build: under an exclusive flock on <key>.lock (a second process waits, saying so, then
//   finds the entry), in <key>.tmp-<pid>/: the project (the embedded RTL and its
//   rast_verilate.cmake, the exported parameter header, the runner's main, the embedded
//   testbench headers it compiles, and a CMakeLists.txt that links rastsim's exported
//   libraries), cmake configure (Verilator runs here) and build with the same compiler;
//   then the runner, manifest and log are kept and the directory renamed to <key> at
//   once, so a reader never sees half an entry.
// - An installed rastsim without its build tree cannot build: the error says so.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "rtlsim/rtl_params.h"

namespace rastsim {

// $RASTSIM_CACHE/<sub>, else $XDG_CACHE_HOME/rastsim/<sub>, else ~/.cache/rastsim/<sub>.
std::string rastsim_cache_dir(const std::string& sub);

// What this binary's build tree provides for on-demand builds (generated at configure
// time by model/rtlsim/CMakeLists.txt: rtl_build_info.cpp).
struct RtlBuildInfo {
  std::string cmake, generator, make_program;      // to configure and build the project
  std::string cxx_compiler, cxx_compiler_id, cxx_launcher, build_type;
  std::string verilator_dir, verilator_version;
  std::string verilated_opt;      // RASTSIM_ONDEMAND_OPT, else RASTSIM_VERILATED_OPT: the generated code's -O level
  std::string link_file;          // the exported libraries and their imported dependencies (CMake)
  std::vector<std::string> libs;  // the static libraries the runner links (hashed into the key)
};
const RtlBuildInfo& rtl_build_info();

struct RtlCacheEntry {
  std::string key;          // 16 hex digits: the directory's name
  std::string dir, runner;  // the entry and its rast_runner
  RtlParams params;         // what it was built with
  std::string built_for;    // the config it was first built for (manifest)
  double build_seconds = 0; // its build's wall time (manifest)
  bool hit = false;         // found in the cache (or built by another process meanwhile)
};

struct RtlBuildOptions {
  std::string cache_dir;  // "" = rastsim_cache_dir("rtl")
  std::string label;      // the config, in messages and the manifest
  // Progress lines (stages, the build's [n/m] steps); a line ending in '\n' is one to
  // keep (waiting, built). Empty: stderr_progress().
  std::function<void(const std::string&)> progress;
};

// Prints progress lines on stderr: on a terminal one updating line (kept lines stay).
std::function<void(const std::string&)> stderr_progress();

// The hash of every build input but the parameters (see the key above). Throws when the
// build tree is missing.
std::string rtl_build_inputs();

// An entry whose model runs `wanted`: found, or built with `build` (which must be
// compatible with `wanted`). Throws with the failing stage's error and the log's path.
RtlCacheEntry find_or_build_rtl_model(const RtlParams& wanted, const RtlParams& build, const RtlBuildOptions& o);

// Every complete entry under `dir` ("" = the default), sorted by key.
std::vector<RtlCacheEntry> rtl_cache_entries(const std::string& dir = "");

// Removes every entry under `dir` ("" = the default), with its lock file and any failed
// build's directory; a key whose lock another process holds (building) is left alone.
// Returns how many entries were removed.
size_t clean_rtl_cache(const std::string& dir = "");

// Runs the entry's runner with `request` (a JSON file in a temporary directory) and
// returns its answer; throws with its error, or when it died.
nlohmann::json run_rtl_runner(const RtlCacheEntry& e, const nlohmann::json& request);

}  // namespace rastsim
