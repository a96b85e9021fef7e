// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep` internals shared by its source files: the points of the cross product,
// the CSV they go into (written a row at a time, read back by --resume) and the two
// backends that run them (local child processes, a Slurm job array).
#pragma once

#include <csignal>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common.h"

namespace rastsim::app::sweep {

struct Axis {
  std::string key;
  std::vector<std::string> values;
};

// One configuration point on one scene: a CSV row.
struct Point {
  std::string scene;
  std::vector<std::string> values;  // one per axis, as given on the command line
  std::string config_hash;          // of the whole resolved config (config_hash())
  std::vector<std::string> args;    // `rastsim simulate ...` without --stats
  int status = -1;                  // exit status; -1 = not run
  std::string error;                // the run's last error line when status != 0
  nlohmann::json stats;
};

// "scene=S key=V ..." for progress lines and error reports.
std::string describe(const Point& p, const std::vector<Axis>& axes);

// A fingerprint (16 hex digits, FNV-1a 64) of every key and value of a resolved config:
// two points with the same scene and hash run the same simulation.
std::string config_hash(const Config& cfg);

// Called with a point's index as soon as its run has finished (status, error and stats set).
using OnDone = std::function<void(size_t)>;

// What ran for a row, its `level` column: the --level ("systemc" or "cosim"), plus "+area"
// with --area. Both change the row's columns (cosim adds cycles_rtl, mismatches, ...;
// --area adds area.*), so they are part of the row key: a row of another level is no
// point of this sweep and runs again.
std::string row_level(const std::string& level, bool area);

// The output CSV. Columns: scene, each swept key, level, config_hash, status, then every stat a
// successful row reported (its JSON flattened, "stages.rop.busy"; an empty value counts as
// absent), in the order first seen going down the rows, each row's own in key order
// (dotted part by part, as the JSON lists them), so the columns depend only on the rows. The row key is (scene as
// given to --scene, level, config_hash). The file is always a complete CSV of every finished
// row: each new row is appended and flushed; a row with a stat the header lacks rewrites
// the file (to a temporary, then renamed); write_all() puts the rows in point order.
class Csv {
 public:
  // `level`: row_level() of this sweep, written in every row it adds.
  Csv(std::string path, const std::vector<Axis>& axes, std::string level);
  // --resume: reads the existing file (if any) and marks the points whose key has an
  // "ok" row there as done (status 0); failed rows are run again. Rows of the file that
  // belong to no point of this sweep are kept after the sweep's own. Returns how many
  // points were found. Throws when the file's leading columns are not this sweep's.
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
  std::vector<std::string> fixed_columns() const;
  void merge_columns(const Cells& row);

  std::string path_;
  std::vector<Axis> axes_;
  std::string level_;
  std::vector<std::string> stat_columns_;
  std::map<size_t, Cells> rows_;          // by point index
  std::vector<size_t> written_;           // point indices in file order
  std::vector<Cells> foreign_;            // resumed rows of no point of this sweep
};

// Columns whose values depend on the host's speed, not on the model: a comparison of two
// sweeps' CSVs leaves them out.
bool is_wall_time_column(const std::string& column);

// `--backend slurm`: the options and the run. Submits the points `todo` (indices into
// `points`) as Slurm job arrays of at most MaxArraySize tasks, each task this binary
// running one point's `rastsim simulate`, its stats and exit status written to a per-task
// file in a work directory; polls squeue until every task has finished, calling on_done
// for each as its file appears; a task that ended without one (cancelled, time limit,
// node failure) fails with the last line of its Slurm output. Returns how many failed.
size_t run_slurm(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 const SweepSlurmOptions& o, const std::string& out_path, const OnDone& on_done);

// SIGINT/SIGTERM set this while a sweep waits (the backends stop and say so).
extern volatile std::sig_atomic_t interrupted;

}  // namespace rastsim::app::sweep
