// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep`: the cross product of scenes and swept config values, each point one
// `rastsim simulate` run of this same binary (SystemC elaborates only once a process):
// child processes, --jobs at a time (--backend local), or a Slurm job array (--backend
// slurm, sweep_slurm.cpp); one CSV row a point with every swept key and stat, appended as
// each finishes (sweep_csv.cpp), and --resume runs only the points the CSV lacks.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "common.h"
#include "rtl/area.h"
#include "rtl/cosim.h"
#include "sweep.h"

namespace rastsim::app {

using namespace sweep;

namespace {

Axis parse_axis(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
    throw std::runtime_error("--set " + arg + ": expected section.key=value[,value...]");
  Axis a{arg.substr(0, eq), {}};
  std::stringstream ss(arg.substr(eq + 1));
  for (std::string v; std::getline(ss, v, ',');)
    if (!v.empty()) a.values.push_back(v);
  return a;
}

class Progress {
 public:
  explicit Progress(size_t total) : total_(total), tty_(isatty(2)) {}
  void update(size_t done, size_t failed, const std::string& what) {
    if (tty_) {
      const int width = 30, filled = int(width * done / std::max<size_t>(total_, 1));
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << done << "/"
                << total_ << (failed ? " (" + std::to_string(failed) + " failed)" : "") << std::flush;
      if (done == total_) std::cerr << "\n";
    } else {
      std::cerr << "sweep: " << done << "/" << total_ << " " << what << "\n";
    }
  }
  bool tty() const { return tty_; }

 private:
  size_t total_;
  bool tty_;
};

// The --set arguments: KEY=V1,V2,... become axes; KEY=V joins the base config's overrides.
std::vector<Axis> split_axes(const std::vector<std::string>& set_args, ConfigOptions& base) {
  std::vector<Axis> axes;
  for (const auto& s : set_args) {
    Axis a = parse_axis(s);
    if (a.values.size() == 1) {
      base.sets.push_back(a.key + "=" + a.values[0]);
      continue;
    }
    axes.push_back(std::move(a));
  }
  return axes;
}

// Every swept value validated up front, so a typo fails before anything runs.
void validate_axes(const Config& cfg, const std::vector<Axis>& axes) {
  for (const auto& a : axes)
    for (const auto& v : a.values) {
      Config c = cfg;
      c.apply_override(a.key + "=" + v);
      c.validate();
    }
}

// The cross product, scene-major, each point with its config's hash and its simulate
// arguments.
std::vector<Point> make_points(const std::vector<std::string>& scenes, const std::vector<Axis>& axes,
                               const ConfigOptions& base, const std::string& level) {
  std::vector<Point> points;
  for (const auto& scene : scenes) {
    std::vector<size_t> idx(axes.size(), 0);
    for (;;) {
      Point p;
      p.scene = scene;
      ConfigOptions c = base;
      for (size_t i = 0; i < axes.size(); ++i) {
        p.values.push_back(axes[i].values[idx[i]]);
        c.sets.push_back(axes[i].key + "=" + p.values.back());
      }
      p.config_hash = config_hash(load_config(c));
      // --level cosim: the RTL's figures beside the SystemC model's (cmd_cosim.cpp).
      p.args = level == "cosim" ? std::vector<std::string>{"cosim", "--simulate-stats", "--scene", scene}
                                : std::vector<std::string>{"simulate", "--quiet", "--scene", scene};
      if (!c.config_path.empty()) p.args.insert(p.args.end(), {"--config", c.config_path});
      for (const auto& s : c.sets) p.args.insert(p.args.end(), {"--set", s});
      points.push_back(std::move(p));
      size_t i = axes.size();
      while (i > 0 && ++idx[i - 1] == axes[i - 1].values.size()) idx[--i] = 0;
      if (i == 0) break;
    }
  }
  return points;
}

// --backend local: runs the points `todo`, `jobs` child processes at once, their stats and
// stderr in `tmp`; returns how many failed.
size_t run_local(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 unsigned jobs, const std::filesystem::path& tmp, const OnDone& on_done) {
  Progress progress(todo.size());
  std::map<pid_t, size_t> running;
  const auto file = [&](size_t i, const char* ext) { return (tmp / (std::to_string(i) + ext)).string(); };
  size_t next = 0, done = 0, failed = 0;
  while (done < todo.size()) {
    while (next < todo.size() && running.size() < jobs) {
      const size_t i = todo[next++];
      std::vector<std::string> args = points[i].args;
      args.insert(args.end(), {"--stats", file(i, ".json")});
      running[spawn_self(args, file(i, ".err"))] = i;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) throw std::runtime_error("sweep: waitpid failed");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    Point& p = points[it->second];
    const size_t i = it->second;
    running.erase(it);
    ++done;
    p.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (p.status == 0) {
      std::ifstream is(file(i, ".json"));
      p.stats = nlohmann::json::parse(is);
    } else {
      ++failed;
      p.error = last_line(file(i, ".err"));
      if (progress.tty()) std::cerr << "\n";
      std::cerr << "sweep: point " << describe(p, axes) << " failed: " << p.error << "\n";
    }
    std::filesystem::remove(file(i, ".json")), std::filesystem::remove(file(i, ".err"));
    on_done(i);
    progress.update(done, failed, describe(p, axes) + (p.status == 0 ? " ok" : " FAILED"));
  }
  return failed;
}

// A point's resolved config: the base, then its swept values.
Config point_config(const Point& p, const std::vector<Axis>& axes, const ConfigOptions& base) {
  ConfigOptions c = base;
  for (size_t i = 0; i < axes.size(); ++i) c.sets.push_back(axes[i].key + "=" + p.values[i]);
  return load_config(c);
}

// `--area`: a point's RTL area (rastsim area, model/rtl/area.h) under "area" in its stats,
// so the CSV gains area.cells, area.flip_flops and area.transistors. Synthesised once a
// distinct RTL parameter set (a tile-size sweep over three scenes: one run a tile size),
// the rest from this map or the on-disk cache.
class AreaColumns {
 public:
  void add(Point& p, const std::vector<Axis>& axes, const ConfigOptions& base) {
    const RtlParams rp = rtl_params_from_config(point_config(p, axes, base));
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
    p.stats["area"] = {{"cells", t.cells}, {"flip_flops", t.flip_flops}, {"transistors", t.transistors}};
  }

 private:
  std::map<std::vector<std::pair<std::string, int>>, AreaReport> done_;
};

// --level cosim: every RTL model the points need, made here before they run (a config no
// shipped model fits is built into the cache once, its progress on this terminal; the
// points' `rastsim cosim` children then find it). A config the RTL cannot run is left to
// its point, which fails with the message.
void prepare_rtl_models(const std::vector<Point>& points, const std::vector<size_t>& todo,
                        const std::vector<Axis>& axes, const ConfigOptions& base) {
  std::set<std::string> seen;  // config hashes
  for (size_t i : todo) {
    const Point& p = points[i];
    if (!seen.insert(p.config_hash).second) continue;
    try {
      cosim::prepare_rtl_model(point_config(p, axes, base));
    } catch (const std::exception& e) {
      std::cerr << "sweep: no RTL model for " << describe(p, axes) << ": " << e.what() << "\n";
    }
  }
}

}  // namespace

namespace sweep {

volatile std::sig_atomic_t interrupted = 0;

std::string describe(const Point& p, const std::vector<Axis>& axes) {
  std::string s = "scene=" + p.scene;
  for (size_t i = 0; i < axes.size(); ++i) s += " " + axes[i].key + "=" + p.values[i];
  return s;
}

std::string config_hash(const Config& cfg) {
  uint64_t h = 14695981039346656037ull;
  for (const auto& [k, v] : cfg.values())
    for (char c : k + "=" + to_string(v) + "\n") h = (h ^ uint8_t(c)) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace sweep

void run_sweep_command(SweepOptions o) {
  if (o.backend != "local" && o.backend != "slurm")
    throw std::runtime_error("--backend " + o.backend + ": expected local or slurm");
  std::vector<Axis> axes = split_axes(o.set_args, o.base);
  validate_axes(load_config(o.base), axes);
  std::vector<Point> points = make_points(o.scenes, axes, o.base, o.level);
  Csv csv(o.out_path, axes, row_level(o.level, o.area));
  if (o.resume) {
    const size_t found = csv.resume(points);
    std::cerr << "sweep: --resume: " << found << " of " << points.size() << " rows already in " << o.out_path << "\n";
  }
  csv.write_all(points);
  std::vector<size_t> todo;
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i].status != 0) todo.push_back(i);
  if (o.level == "cosim") prepare_rtl_models(points, todo, axes, o.base);
  AreaColumns area;
  const OnDone on_done = [&](size_t i) {
    if (o.area && points[i].status == 0) area.add(points[i], axes, o.base);
    csv.add(points[i], i);
  };
  size_t failed = 0;
  if (o.backend == "slurm") {
    failed = run_slurm(points, todo, axes, o.slurm, o.out_path, on_done);
  } else {
    const auto tmp = std::filesystem::temp_directory_path() / ("rastsim-sweep-" + std::to_string(getpid()));
    std::filesystem::create_directories(tmp);
    failed = run_local(points, todo, axes, o.jobs, tmp, on_done);
    std::filesystem::remove_all(tmp);
  }
  csv.write_all(points);
  std::cerr << "sweep: wrote " << points.size() << " rows to " << o.out_path
            << (todo.size() < points.size() ? " (" + std::to_string(points.size() - todo.size()) + " resumed)" : "")
            << "\n";
  if (failed) throw std::runtime_error(std::to_string(failed) + " of " + std::to_string(points.size()) +
                                       " sweep points failed (see above)");
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
                  "KEY=V fixes one")
      ->type_name("KEY=VALUES")
      ->allow_extra_args(false);
  cmd->add_option("--out,-o", o.out_path,
                  "CSV to write: scene, each swept key, level (--level, +area with --area), config_hash, "
                  "status, then every stat; each row is appended as its run finishes, and at the end the rows "
                  "are put in sweep order")
      ->required();
  cmd->add_flag("--resume", o.resume,
                "Keep the rows already in --out whose scene, level (--level and --area) and config_hash (a "
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
  cmd->add_option("--jobs,-j", o.jobs, "Local backend: simulations run at once (default: the number of cores)")
      ->check(CLI::Range(1u, 1024u));
  cmd->add_option("--backend", o.backend,
                  "local: child processes on this machine; slurm: one Slurm job array (sbatch --array), a task "
                  "a point, then the rows gathered into --out (the binary, scenes, config and --slurm-workdir "
                  "must be at the same paths on the compute nodes)")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  cmd->add_option("--slurm-partition", o.slurm.partition, "Slurm backend: sbatch --partition (default: the cluster's)");
  cmd->add_option("--slurm-time", o.slurm.time,
                  "Slurm backend: sbatch --time, the limit of one task, e.g. 10:00 or 1-00:00:00 (default: the "
                  "partition's)");
  cmd->add_option("--slurm-workdir", o.slurm.workdir,
                  "Slurm backend: where the job script and each task's stats, exit status and output go, in a "
                  "subdirectory per sweep removed when every task succeeded (default: OUT.slurm beside --out; "
                  "must be shared with the compute nodes)");
  cmd->add_option("--slurm-arg", o.slurm.sbatch_args,
                  "Slurm backend: one more sbatch option, verbatim (repeatable), e.g. --slurm-arg=--mem=2G "
                  "--slurm-arg=--account=arch")
      ->allow_extra_args(false);
  cmd->add_option("--slurm-poll", o.slurm.poll_seconds,
                  "Slurm backend: seconds between squeue polls while waiting for the array")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  cmd->callback([] { run_sweep_command(o); });
}

}  // namespace rastsim::app
