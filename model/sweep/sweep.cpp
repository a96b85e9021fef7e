// SPDX-License-Identifier: Apache-2.0
// run_sweep (sweep.h): the points planned, the CSV resumed, the RTL models and area
// figures a sweep needs, and the backend that runs the points.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <set>
#include <stdexcept>

#include "rtlsim/area.h"
#include "rtlsim/cosim.h"
#include "sweep/sweep.h"
#include "util/atomic_file.h"
#include "util/interrupt.h"
#include "util/process.h"

namespace rastsim::sweep {

volatile std::sig_atomic_t interrupted = 0;

namespace {

// `--area`: a point's RTL area (rastsim area, model/rtlsim/area.h) under "area" in its stats,
// so the CSV gains area.cells, area.flip_flops, area.transistors (the memory system's
// counted arrays included) and area.storage_transistors. Synthesised once a
// distinct RTL parameter set (a tile-size sweep over three scenes: one run a tile size),
// the rest from this map or the on-disk cache.
class AreaColumns {
 public:
  void add(Point& p, const std::vector<Axis>& axes, const BaseConfig& base) {
    const ArchParams arch = ArchParams::resolve(point_config(p, axes, base));  // each point resolves its own config
    const RtlParams rp = rtl_params(arch);
    const auto key = rtl_params_named(rp);
    auto it = done_.find(key);
    if (it == done_.end()) {
      AreaOptions ao;
      ao.progress = [&](const std::string& line) { std::cerr << "\r\033[Ksweep: area " << line << std::flush; };
      if (!isatty(2)) ao.progress = {};
      std::cerr << "sweep: area of " << describe(p, axes) << (isatty(2) ? "" : "\n");
      it = done_.emplace(key, synthesize_area(rp, ao)).first;
      if (isatty(2)) std::cerr << "\r\033[K";
      std::cerr << "sweep: area " << (it->second.from_cache ? "from the cache" : "synthesised") << ": "
                << it->second.total.cells << " cells\n";
    }
    const AreaCounts& t = it->second.total;
    // The memory system's arrays (not synthesised) follow the point's memory keys, which
    // the RTL parameters do not hold: counted a point.
    uint64_t storage = 0;
    for (const StorageArray& a : design_storage(arch)) storage += a.transistors;
    p.stats["area"] = {{"cells", t.cells}, {"flip_flops", t.flip_flops}, {"transistors", t.transistors + storage},
                       {"storage_transistors", storage}};
  }

 private:
  std::map<std::vector<std::pair<std::string, int>>, AreaReport> done_;
};

// --level cosim: every RTL model the points need, made here before they run (a config no
// shipped model fits is built into the cache once, its progress on this terminal; the
// points' `rastsim cosim` children then find it). A config the RTL cannot run is left to
// its point, which fails with the message.
void prepare_rtl_models(const std::vector<Point>& points, const std::vector<size_t>& todo,
                        const std::vector<Axis>& axes, const BaseConfig& base) {
  std::set<std::string> seen;  // config hashes
  for (size_t i : todo) {
    const Point& p = points[i];
    if (!seen.insert(p.config_hash).second) continue;
    try {
      rtlsim::prepare_rtl_model(ArchParams::resolve(point_config(p, axes, base)));
    } catch (const std::exception& e) {
      std::cerr << "sweep: no RTL model for " << describe(p, axes) << ": " << e.what() << "\n";
    }
  }
}

// Runs the points `todo` on the chosen backend; returns how many failed.
size_t run_points(const SweepOptions& o, std::vector<Point>& points, const std::vector<size_t>& todo,
                  const std::vector<Axis>& axes, const OnDone& on_done) {
  if (o.backend == "slurm") return run_slurm(points, todo, axes, o.slurm, o.out_path, on_done);
  const TempDir tmp("rastsim-sweep");  // the points' stats and error files
  return run_local(points, todo, axes, o.jobs, tmp.path(), on_done);
}

// What an interrupted sweep kept (the rows of the points that finished: the CSV gets each
// as it finishes) and the command line that runs the rest.
std::string interrupted_message(const Interrupted& e, const SweepOptions& o, const std::vector<Point>& points) {
  size_t finished = 0;
  for (const Point& p : points) finished += p.status != -1;
  std::vector<std::string> argv = this_command_line();
  if (std::find(argv.begin(), argv.end(), "--resume") == argv.end()) argv.push_back("--resume");
  return "sweep: " + std::string(e.what()) + ": " + std::to_string(finished) + " of " + std::to_string(points.size()) +
         " rows finished and kept in " + o.out_path + "; the running points were stopped and their files removed. " +
         "Run the other " + std::to_string(points.size() - finished) + " with:\n  " + shell_command(argv) + "\n";
}

}  // namespace

void run_sweep(const SweepOptions& o, const BaseConfig& base, const std::vector<Axis>& axes) {
  // SIGINT and SIGTERM unwind instead of ending the process (util/interrupt.h): the points
  // running are stopped, the temporary folder removed, and the message says what was kept.
  const InterruptScope scope;
  if (o.backend != "local" && o.backend != "slurm")
    throw std::runtime_error("--backend " + o.backend + ": expected local or slurm");
  validate_axes(base.resolved, axes);
  std::vector<Point> points = make_points(o.scenes, axes, base, o.level);
  Csv csv(o.out_path, axes, fixed_sets(base.sets, axes), row_level(o.level, o.area));
  if (o.resume) {
    const size_t found = csv.resume(points);
    std::cerr << "sweep: --resume: " << found << " of " << points.size() << " rows already in " << o.out_path << "\n";
  }
  csv.write_all(points);
  std::vector<size_t> todo;
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i].status != 0) todo.push_back(i);
  AreaColumns area;
  const OnDone on_done = [&](size_t i) {
    if (o.area && points[i].status == 0) area.add(points[i], axes, base);
    csv.add(points[i], i);
  };
  size_t failed = 0;
  try {
    if (o.level == "cosim") prepare_rtl_models(points, todo, axes, base);
    failed = run_points(o, points, todo, axes, on_done);
  } catch (const Interrupted& e) {
    std::cerr << (isatty(2) ? "\n" : "") << interrupted_message(e, o, points);
    throw;
  }
  csv.write_all(points);
  std::cerr << "sweep: wrote " << points.size() << " rows to " << o.out_path
            << (todo.size() < points.size() ? " (" + std::to_string(points.size() - todo.size()) + " resumed)" : "")
            << "\n";
  if (failed) throw std::runtime_error(std::to_string(failed) + " of " + std::to_string(points.size()) +
                                       " sweep points failed (see above)");
}

}  // namespace rastsim::sweep
