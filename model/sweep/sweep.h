// SPDX-License-Identifier: Apache-2.0
// The sweep engine behind `rastsim sweep`: the cross product of scenes and swept config
// values (plan.cpp), each point one `rastsim simulate` (or `cosim`) run of this same
// binary, since SystemC elaborates only once a process; the points run as child
// processes, a number at a time (local.cpp), or as a Slurm job array (slurm.cpp); one CSV
// row a point with every swept key and stat, appended as each finishes and read back by
// --resume (csv.cpp); sweep.cpp joins them (run_sweep).
#pragma once

#include <csignal>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/config.h"

namespace rastsim::sweep {

struct Axis {
  std::string key;
  std::vector<std::string> values;
};

// `--backend slurm`: where the job array goes and how it is watched.
struct SlurmOptions {
  std::string partition, time;           // sbatch --partition, --time ("" = the cluster's default)
  std::string workdir;                   // per-task files ("" = OUT.slurm next to the CSV)
  std::vector<std::string> sbatch_args;  // more sbatch options, verbatim
  double poll_seconds = 5;               // squeue every this often
};

// How a sweep runs: scenes, CSV path, simulations run at once, the level, the backend and
// --resume (the config comes apart: BaseConfig, axes).
struct SweepOptions {
  std::vector<std::string> scenes;
  std::string out_path;
  unsigned jobs = 1;
  bool area = false;  // add area.cells, area.flip_flops, area.transistors (rastsim area) to each row
  std::string level = "systemc";   // "systemc" (rastsim simulate) or "cosim" (rastsim cosim: + cycles_rtl, mismatches)
  bool resume = false;             // keep the rows already in out_path; run only the others
  std::string backend = "local";   // "local" (child processes) or "slurm" (a job array)
  SlurmOptions slurm;
};

// The config every point starts from: resolved (the file, then the fixed overrides), and
// as given, for the points' command lines.
struct BaseConfig {
  Config resolved;
  std::string path;               // --config ("" = none)
  std::vector<std::string> sets;  // the fixed overrides, KEY=V
};

// The --set arguments: KEY=V1,V2,... become axes; KEY=V is appended to `fixed`.
std::vector<Axis> split_axes(const std::vector<std::string>& set_args, std::vector<std::string>& fixed);

// A fixed --set of a sweep as a CSV column: the key and the value of every row.
struct FixedSet {
  std::string key, value;
};
// The fixed overrides (KEY=V, in order) as columns: each key once, in the order of its first
// --set, with its last value (the one the config keeps); a key that is also swept is left
// to its axis (the swept value is applied last).
std::vector<FixedSet> fixed_sets(const std::vector<std::string>& sets, const std::vector<Axis>& axes);

// Runs the sweep: every swept value validated first, then the points the CSV lacks (all
// of them without --resume); throws when a point failed, after writing every row.
void run_sweep(const SweepOptions& o, const BaseConfig& base, const std::vector<Axis>& axes);

// One configuration point on one scene: a CSV row.
struct Point {
  std::string scene;
  std::vector<std::string> values;  // one per axis, as given on the command line
  std::string config_hash;          // of the whole resolved config (config_hash(), config.h): two
                                    // points with the same scene and hash run the same simulation
  std::vector<std::string> args;    // `rastsim simulate ...` without --stats
  int status = -1;                  // exit status; -1 = not run
  std::string error;                // the run's last error line when status != 0
  nlohmann::json stats;
};

// Every swept value validated up front, so a typo fails before anything runs.
void validate_axes(const Config& cfg, const std::vector<Axis>& axes);

// The cross product, scene-major, each point with its config's hash and its `rastsim
// simulate` (--level cosim: `rastsim cosim`) arguments.
std::vector<Point> make_points(const std::vector<std::string>& scenes, const std::vector<Axis>& axes,
                               const BaseConfig& base, const std::string& level);

// A point's resolved config: the base, then its swept values.
Config point_config(const Point& p, const std::vector<Axis>& axes, const BaseConfig& base);

// "scene=S key=V ..." for progress lines and error reports.
std::string describe(const Point& p, const std::vector<Axis>& axes);

// Called with a point's index as soon as its run has finished (status, error and stats set).
using OnDone = std::function<void(size_t)>;

// What ran for a row, its `level` column: the --level ("systemc" or "cosim"), plus "+area"
// with --area. Both change the row's columns (cosim adds cycles_rtl, mismatches, ...;
// --area adds area.*), so they are part of the row key: a row of another level is no
// point of this sweep and runs again.
std::string row_level(const std::string& level, bool area);

// The output CSV. Columns: scene, each swept key, level, config_hash, status, each fixed
// --set key (fixed_sets()), rastsim_version (of the binary that ran the row, from its
// stats' provenance), then every stat a successful row reported (its JSON flattened,
// "stages.rop.busy", its provenance left out: the columns before hold it; an empty value
// counts as absent), in the order first seen going down the rows, each row's own in key
// order (dotted part by part, as the JSON lists them), so the columns depend only on the
// rows. The row key is (scene as given to --scene, level, config_hash). The file is always
// a complete CSV of every finished row: each new row is appended and flushed; a row with a
// stat the header lacks rewrites the file (to a temporary, then renamed); write_all() puts
// the rows in point order.
class Csv {
 public:
  // `fixed`: the sweep's fixed_sets(); `level`: row_level() of this sweep, written in
  // every row it adds.
  Csv(std::string path, const std::vector<Axis>& axes, std::vector<FixedSet> fixed, std::string level);
  // --resume: reads the existing file (if any) and marks the points whose key has an
  // "ok" row there as done (status 0); failed rows are run again. Rows of the file that
  // belong to no point of this sweep are kept after the sweep's own. Returns how many
  // points were found. Throws when the file's leading columns (up to rastsim_version:
  // other swept or fixed keys) are not this sweep's.
  size_t resume(std::vector<Point>& points);
  // Writes the file anew: the header and every row known, in point order, then the kept
  // foreign rows (at the start, the resumed rows; at the end, all of them).
  void write_all(const std::vector<Point>& points);
  // Adds the finished point `i` and appends its row.
  void add(const Point& p, size_t i);

 private:
  using Cells = std::map<std::string, std::string>;
  Cells cells_of(const Point& p) const;
  std::string line_of(const Cells& row) const;
  void rewrite();  // header and the rows in written_ order, then foreign_
  std::vector<std::string> leading_columns() const;  // every column before the stats
  void merge_columns(const Cells& row);

  std::string path_;
  std::vector<Axis> axes_;
  std::vector<FixedSet> fixed_;
  std::string level_;
  std::vector<std::string> stat_columns_;
  std::map<size_t, Cells> rows_;          // by point index
  std::vector<size_t> written_;           // point indices in file order
  std::vector<Cells> foreign_;            // resumed rows of no point of this sweep
};

// Columns whose values depend on the host's speed, not on the model: a comparison of two
// sweeps' CSVs leaves them out.
bool is_wall_time_column(const std::string& column);

// `--backend local`: runs the points `todo` (indices into `points`), `jobs` child
// processes at once, their stats and stderr in `tmp`; returns how many failed. On SIGINT
// or SIGTERM (util/interrupt.h) the running ones are stopped and Interrupted is thrown:
// the points that finished keep their status (on_done has been called for each).
size_t run_local(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 unsigned jobs, const std::filesystem::path& tmp, const OnDone& on_done);

// `--backend slurm`: the options and the run. Submits the points `todo` (indices into
// `points`) as Slurm job arrays of at most MaxArraySize tasks, each task this binary
// running one point's `rastsim simulate`, its stats and exit status written to a per-task
// file in a work directory; polls squeue until every task has finished, calling on_done
// for each as its file appears; a task that ended without one (cancelled, time limit,
// node failure) fails with the last line of its Slurm output. Returns how many failed.
size_t run_slurm(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 const SlurmOptions& o, const std::string& out_path, const OnDone& on_done);

// SIGINT/SIGTERM set this while a sweep waits (the backends stop and say so).
extern volatile std::sig_atomic_t interrupted;

}  // namespace rastsim::sweep
