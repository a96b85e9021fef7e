// SPDX-License-Identifier: Apache-2.0
// Options and helpers shared by every `rastsim` subcommand.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "config/arch_params.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "sweep/sweep.h"

namespace rastsim::app {

// --config FILE and repeatable --set section.key=value, on every subcommand.
struct ConfigOptions {
  std::string config_path;
  std::vector<std::string> sets;
};
void add_config_options(CLI::App* cmd, ConfigOptions& o);
// The required --scene FILE of the commands that run one scene.
void add_scene_option(CLI::App* cmd, std::string& scene_path);
// Defaults, then the file, then the overrides in order; validated.
Config load_config(const ConfigOptions& o);

// load_config, resolved into the run's typed parameters (config/arch_params.h): the one
// place a command turns its config into what the model reads.
ArchParams resolve_arch(const ConfigOptions& o);
// resolve_arch for a run of one scene (scene/scene_params.h): an OBJ mesh draws with
// scene.obj_depth_func.
ArchParams resolve_arch(const ConfigOptions& o, const std::string& scene_path);

// What produced a stats JSON, its "provenance" object (docs/provenance.md): rastsim's
// version, the command line and working directory, the config file and every --set in
// order, the resolved config as canonical TOML (config_toml) and its config_hash, the
// scene file and the FNV-1a 64 hash of its bytes as stored (null without a scene).
nlohmann::json provenance(const ConfigOptions& o, const Config& resolved, const std::string& scene_path);

// Writes JSON to a file (pretty, with a trailing newline), whole or not at all
// (util/atomic_file.h); "-" means stdout.
void write_json(const std::string& path, const nlohmann::json& j);

// Where a command's human text (summary, tables, notes) goes: stdout, or stderr when
// `--stats -` puts the JSON on stdout (stdout then carries only JSON), or nowhere with
// -q/--quiet. Errors and warnings go to std::cerr, never here.
std::ostream& summary_stream(const std::string& stats_path, bool quiet);

// -q/--quiet, spelled and described alike on every command; `what` is what it drops.
void add_quiet_flag(CLI::App* cmd, bool& quiet, const std::string& what);

// Throws when more than one {option, path} has the path "-": two outputs cannot share
// stdout (a script could not tell them apart).
void check_one_stdout(const std::vector<std::pair<std::string, std::string>>& option_paths);

// Runs `rastsim simulate` on `scene` with the same config options in a child process and
// returns its stats JSON; throws with the child's error line when it fails.
// `extra`: more simulate options (e.g. {"--frames", "3:4"}).
nlohmann::json simulate_in_child(const ConfigOptions& o, const std::string& scene,
                                 const std::vector<std::string>& extra = {});

// `rastsim render` as a plain function: every option of the command, then the run.
struct RenderOptions {
  ConfigOptions config;
  std::string scene_path, out_path, stats_path, frag_path;
  bool quiet = false;
  int threads = 0;  // render --threads: 0 = every core (std::thread::hardware_concurrency)
  std::string frames;  // --frames A:B ("" = every frame; app/frame_output.h)
};
void run_render_command(const RenderOptions& o);

// `rastsim simulate` as a plain function; the stall options are for tests.
struct SimulateOptions {
  ConfigOptions config;
  std::string scene_path, out_path, stats_path, vcd_path, frag_path;
  std::string timeline_path;                // trace-event JSON ("" = none)
  std::string mem_trace_path;               // DRAM requests, DRAMsim3's format ("" = none)
  uint64_t timeline_max_events = 0;  // above it the timeline is quantized (0: sc::SimOptions's)
  std::string heatmap_path, heatmap_data_path;  // PNG and per-tile JSON ("" = none)
  std::string heatmap_stage = "all";        // a tile_heat stage (timing/stage_table.h) or all
  double stall_probability = 0;  // 0 = off
  std::optional<double> sample;  // --sample F in (0, 1]: the sampled level (docs/fidelity.md)
  uint64_t seed = 1;             // --seed: the stall injection's and --sample/--tolerance's random choices
  std::string tolerance;         // --tolerance P%: the cheapest level within P ("" = off)
  std::string frames;            // --frames A:B ("" = every frame; app/frame_output.h)
  std::optional<double> frame_sample;  // --frame-sample F: the frame-sampled level
  bool quiet = false;
};
void run_simulate_command(const SimulateOptions& o);

// `rastsim estimate` as a plain function: the analytic bounds and estimate, no simulation.
struct EstimateOptions {
  ConfigOptions config;
  std::string scene_path, stats_path;
  std::string frames;  // --frames A:B ("" = every frame)
  bool quiet = false;
};
void run_estimate_command(const EstimateOptions& o);

// `rastsim monitor` as a plain function: every option of the command, then the run.
struct MonitorOptions {
  ConfigOptions config;
  std::string signal_path, out_path, stats_path, clock;
  bool quiet = false;
};
void run_monitor_command(const MonitorOptions& o);

// `rastsim scanout` as a plain function: every option of the command, then the run.
struct ScanoutOptions {
  ConfigOptions config;
  std::string scene_path, out_path, signal_path, stats_path, lines_arg;
  bool quiet = false;
  int64_t raster_cycles = -1;  // < 0: untimed scan-out
  bool timed = false;          // take raster_cycles from a `rastsim simulate` child
  int signal_frames = 1;
};
void run_scanout_command(const ScanoutOptions& o);

// `rastsim sweep` as a plain function: the sweep's own options (scenes, CSV, jobs, level,
// backend, --resume: sweep/sweep.h), the base config and the --set arguments (KEY=V1,V2,...
// sweeps a key, KEY=V fixes one).
struct SweepOptions : sweep::SweepOptions {
  ConfigOptions base;
  std::vector<std::string> set_args;
  bool quiet = false;  // -q: the engine's progress lines dropped
};
void run_sweep_command(SweepOptions o);

// `rastsim area` as a plain function: every option of the command, then the run.
struct AreaCommandOptions {
  ConfigOptions config;
  std::string stats_path, top;
  bool no_cache = false, quiet = false;
  bool one_process = false;  // rast_top in one Yosys process (default: one a module)
  int jobs = 2;              // Yosys processes at once
};
void run_area_command(const AreaCommandOptions& o);

// Each subcommand registers itself; main() calls these in order.
void register_config(CLI::App& app);
void register_render(CLI::App& app);
void register_simulate(CLI::App& app);
void register_sweep(CLI::App& app);
void register_cosim(CLI::App& app), register_export_rtl(CLI::App& app), register_area(CLI::App& app);
void register_scanout(CLI::App& app), register_monitor(CLI::App& app);
void register_fit(CLI::App& app);
void register_import_apitrace(CLI::App& app);
void register_estimate(CLI::App& app);
void register_coverage_error(CLI::App& app);  // model/aa: masks against exact area coverage
void register_recip_grid(CLI::App& app);  // ref/study/recip_grid: newton reciprocal settings against exact
void register_dram_replay(CLI::App& app);  // timing/dram: a DRAMsim3-format trace through the DRAM model

}  // namespace rastsim::app
