// SPDX-License-Identifier: Apache-2.0
// Area of the RTL: the raster pipeline (rtl/rast_top.sv) built with a config's exported
// parameters, and the 2D engine beside it (rtl/rast_engine2d.sv), synthesised with Yosys
// into generic gates (docs/area.md).
//
// - Method: Yosys `synth -noabc`, async resets turned into sync logic and every flop
//   legalised to a plain D flop ($_DFF_P_), then `abc -fast` and `stat -tech cmos`: cells
//   by type, flip-flops and Yosys' CMOS transistor estimate. Relative area only: no cell
//   library, no wires, no placement.
// - Per stage: the modules rast_top instantiates (grouped by module, instances summed),
//   rast_top's own glue logic, and rast_engine2d; each counted with its submodules.
// - Split: rast_top is elaborated once for its derived modules, then each is synthesised
//   in its own Yosys process with its submodules as blackboxes (at most two at once), and
//   the own gates x instance counts are summed up the hierarchy here: no process holds
//   the whole pipeline (one did not fit in 14.5 GB for the default config).
// - Cache: one JSON a Yosys run (a module of rast_top, rast_engine2d, or the one --top
//   module), named by a hash of everything that decides it (Yosys version, the script,
//   the embedded RTL files that module reads (area_sources_key: an edit to a file it does
//   not reach keeps the entry), the parameter header when the run uses it, the top), in
//   area_cache_dir(): a second call with the same RTL parameters reads it back at once,
//   and rast_engine2d (no config parameter) is synthesised once for every config.
// - The RTL sources are compiled into the binary (rtl_sources.h), so no run reads the
//   source tree.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rtlsim/area_memory.h"
#include "rtlsim/rtl_params.h"
#include "rtlsim/rtl_sources.h"

namespace rastsim {

// Gate counts of one module with everything below it.
struct AreaCounts {
  uint64_t cells = 0;         // generic gate cells, flops included
  uint64_t flip_flops = 0;    // $_DFF_P_ cells (1 bit each)
  uint64_t transistors = 0;   // Yosys' CMOS estimate (stat -tech cmos)
  uint64_t instances = 1;     // how many instances the figures sum (rast_fifo: one a FIFO)
  std::map<std::string, uint64_t> cells_by_type;  // "$_AND_" -> count

  AreaCounts& operator+=(const AreaCounts& o);
};

struct AreaReport {
  AreaCounts total;                         // the whole design (transistors: the storage rows' too)
  std::map<std::string, AreaCounts> stages; // module name -> its figures ("rast_top.glue": rast_top's own logic)
  std::string top;                          // "" = rast_top and rast_engine2d; else the one module synthesised
  std::string yosys_version;
  std::string key;                          // cache key (hex): the cache file's name for one run, else a hash of the runs' keys
  double synth_seconds = 0;                 // Yosys wall time of the runs when they ran (the cached value on a hit)
  double cpu_seconds = 0;                   // Yosys' own CPU time (user + system), summed over its processes
  double peak_mb = 0;                       // the largest Yosys process's peak memory, MB
  uint64_t modules = 0;                     // Yosys processes the figures come from (split: one a module)
  bool from_cache = false;                  // every run read from the cache
  std::vector<std::pair<std::string, int>> parameters;  // the exported RTL parameters
  // Counted, not synthesised: the memory system's arrays (area_memory.h), added by the
  // caller with add_storage; empty when the memory system is off or for one module.
  std::vector<StorageArray> storage;
};

struct AreaOptions {
  std::string top;        // "" (whole design), "rast_top", "rast_engine2d" or a module under rast_top
  // A standalone root's parameters (root_rtl_params: rast_recip's SEED_BITS, ITERATIONS),
  // set at elaboration (Yosys `hierarchy -chparam`); empty: the module's defaults.
  std::vector<std::pair<std::string, int>> root_parameters;
  std::string cache_dir;  // "" = area_cache_dir()
  bool use_cache = true;
  // rast_top one Yosys process a derived module (submodules as blackboxes), the sums
  // taken here; false: the whole hierarchy in one process (needs several GB on the wide
  // configs; tests compare the two).
  bool split = true;
  int jobs = 2;  // Yosys processes at once in a split run (2 cores, shared machine)
  // Called with one line of progress (a Yosys pass starting, a run finishing).
  std::function<void(const std::string&)> progress;
};

// $RASTSIM_CACHE/area, else $XDG_CACHE_HOME/rastsim/area, else ~/.cache/rastsim/area.
std::string area_cache_dir();

// The Yosys on PATH ("yosys" or $RASTSIM_YOSYS); throws naming the Debian package when absent.
std::string find_yosys();

// The modules AreaOptions::top can name, from the embedded sources alone (no Yosys):
// rast_top, rast_engine2d, and each module under rast_top whose every instantiation
// carries the same parameter overrides (one module once elaborated). A module
// instantiated with several parameter sets (rast_fifo, rast_hold) is not among them.
std::vector<std::string> area_reportable_tops();

// Synthesises (or reads from the cache) the area of the RTL built with `p`. Throws
// std::runtime_error with Yosys' error line when synthesis fails.
AreaReport synthesize_area(const RtlParams& p, const AreaOptions& o = {});

// The report as JSON: cells, flip_flops, transistors, cells_by_type, stages.<module>.*,
// storage (the arrays in order: name, bits, kind "sram" or "flip_flops", transistors),
// and how it was made (top, yosys, key, synth_seconds, from_cache, parameters).
nlohmann::json area_to_json(const AreaReport& r);
AreaReport area_from_json(const nlohmann::json& j);

// The RTL files a module's synthesis reads, sorted by name: the file declaring it
// (module, package or interface) and, transitively, the files of the modules it
// instantiates, the packages it names (`pkg::`) and the files it `include`s (among
// `sources`; the generated rast_params.vh is keyed by its text apart). Throws when no
// source declares `module`.
std::vector<std::string> area_module_files(const std::string& module,
                                           const std::vector<RtlSource>& sources = rtl_sources());
// The hash (hex) of those files' names and texts: the sources' part of every area cache
// key of `module` (a split run's module entry, the elaborated hierarchy and a one-process
// run by their root), so editing a file it does not reach keeps its entries.
std::string area_sources_key(const std::string& module, const std::vector<RtlSource>& sources = rtl_sources());

// Turns Yosys' `stat -json -tech cmos` of a hierarchical design into per-module totals
// (each module with its submodules); `root` is the base name of the synthesised top.
// Exposed for tests.
AreaReport area_from_yosys_stat(const nlohmann::json& stat, const std::string& root);

}  // namespace rastsim
