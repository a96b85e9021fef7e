// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep`: the command-line options of the sweep engine (model/sweep/sweep.h): the
// cross product of scenes and swept config values, each point one `rastsim simulate` run
// of this same binary, one CSV row a point, --resume running only the points the CSV lacks.
#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "common.h"

namespace rastsim::app {

namespace {

// -q: the sweep engine's progress, resume and per-point lines (all on stderr) dropped
// while it runs; the error a failed sweep ends with still prints (main.cpp).
class StderrMuted {
 public:
  explicit StderrMuted(bool on) : saved_(on ? std::cerr.rdbuf(nullptr) : nullptr), on_(on) {}
  ~StderrMuted() {
    if (!on_) return;
    std::cerr.rdbuf(saved_);
    std::cerr.clear();
  }
  StderrMuted(const StderrMuted&) = delete;
  StderrMuted& operator=(const StderrMuted&) = delete;

 private:
  std::streambuf* saved_;
  bool on_;
};

}  // namespace

void run_sweep_command(SweepOptions o) {
  if (o.out_path.empty()) throw std::runtime_error("sweep: --output CSV is required");
  const std::vector<sweep::Axis> axes = sweep::split_axes(o.set_args, o.base.sets);
  const StderrMuted muted(o.quiet);
  sweep::run_sweep(o, {load_config(o.base), o.base.config_path, o.base.sets}, axes);
}

void register_sweep(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "sweep", "Simulate the cross product of scenes and config values in parallel; one CSV row a run");
  static SweepOptions o;
  o.jobs = std::max(1u, std::thread::hardware_concurrency());
  cmd->add_option("--config,-c", o.base.config_path, "Base architecture config (TOML)")->check(CLI::ExistingFile);
  cmd->add_option("--scene,-s", o.scenes, "Scene (repeatable): a trace or an OBJ")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", o.set_args,
                  "KEY=V1,V2,... sweeps a key over values (repeatable; the sweep is the cross product); "
                  "KEY=V fixes one; each key once, each value once")
      ->type_name("KEY=VALUES")
      ->allow_extra_args(false);
  cmd->add_option("-o,--output", o.out_path,
                  "CSV to write (required): scene, each swept key, level (--level, +area with --area), config_hash, "
                  "status, each fixed --set key, rastsim_version, then every stat; each row is appended as its "
                  "run finishes, and at the end the rows are put in sweep order");
  cmd->add_option("--out", o.out_path, "Old name of --output")->group("");
  cmd->add_flag("--resume", o.resume,
                "Keep the rows already in --output whose scene, level (--level and --area) and config_hash (a "
                "hash of the whole resolved config) are points of this sweep and whose status is ok; run only "
                "the others (failed rows, and rows of another level, run again)");
  cmd->add_flag("--area", o.area,
                "Add area.cells, area.flip_flops, area.transistors (rastsim area, Yosys; cached per RTL "
                "parameter set) to every row");
  cmd->add_option("--level", o.level,
                  "systemc: each point a `rastsim simulate`; cosim: a `rastsim cosim`, its row the SystemC stats "
                  "plus cycles_rtl, mismatches and cycle_error ((cycles - cycles_rtl) / cycles_rtl); a config no "
                  "shipped RTL model fits is built into the RTL cache first, once (docs/rtl.md)")
      ->check(CLI::IsMember({"systemc", "cosim"}))
      ->capture_default_str();
  cmd->add_option("--jobs,-j", o.jobs,
                  "Local backend: simulations run at once, each a child process (default: the number of cores)")
      ->check(CLI::Range(1u, 1024u));
  cmd->add_option("--backend", o.backend,
                  "local: child processes on this machine; slurm: one Slurm job array (sbatch --array), a task "
                  "a point, then the rows gathered into --output (the binary, scenes, config and --slurm-workdir "
                  "must be at the same paths on the compute nodes)")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  cmd->add_option("--slurm-partition", o.slurm.partition, "Slurm backend: sbatch --partition (default: the cluster's)");
  cmd->add_option("--slurm-time", o.slurm.time,
                  "Slurm backend: sbatch --time, the limit of one task, e.g. 10:00 or 1-00:00:00 (default: the "
                  "partition's)");
  cmd->add_option("--slurm-workdir", o.slurm.workdir,
                  "Slurm backend: where the job script and each task's stats, exit status and output go, in a "
                  "subdirectory per sweep removed when every task succeeded (default: OUT.slurm beside --output; "
                  "must be shared with the compute nodes)");
  cmd->add_option("--slurm-arg", o.slurm.sbatch_args,
                  "Slurm backend: one more sbatch option, verbatim (repeatable), e.g. --slurm-arg=--mem=2G "
                  "--slurm-arg=--account=arch")
      ->allow_extra_args(false);
  cmd->add_option("--slurm-poll", o.slurm.poll_seconds,
                  "Slurm backend: seconds between squeue polls while waiting for the array")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  add_quiet_flag(cmd, o.quiet, "progress, resume or per-point lines; each row's status is in the CSV");
  cmd->callback([] { run_sweep_command(o); });
}

}  // namespace rastsim::app
