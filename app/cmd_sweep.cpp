// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep`: the cross product of scenes and swept config values, each point one
// `rastsim simulate` child process of this same binary (SystemC elaborates only once a
// process), run --jobs at a time; one CSV row a point with every swept key and stat.
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

namespace rastsim::app {

namespace {

struct Axis {
  std::string key;
  std::vector<std::string> values;
};

struct Point {
  std::string scene;
  std::vector<std::string> values;  // one per axis
  std::string stats_path, err_path;
  int status = -1;                  // exit status; -1 = not run
  nlohmann::json stats;
};

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

// "stages": {"rop": {"busy": 3}} -> "stages.rop.busy" = 3, in document order.
void flatten(const nlohmann::json& j, const std::string& prefix, std::vector<std::pair<std::string, nlohmann::json>>& out) {
  for (const auto& [k, v] : j.items()) {
    const std::string key = prefix.empty() ? k : prefix + "." + k;
    if (v.is_object()) flatten(v, key, out);
    else out.emplace_back(key, v);
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
std::string csv_value(const nlohmann::json& v) { return csv_field(v.is_string() ? v.get<std::string>() : v.dump()); }

std::string describe(const Point& p, const std::vector<Axis>& axes) {
  std::string s = "scene=" + p.scene;
  for (size_t i = 0; i < axes.size(); ++i) s += " " + axes[i].key + "=" + p.values[i];
  return s;
}

// Starts `rastsim simulate` for one point; stdout discarded, stderr to the point's file.
pid_t spawn(const Point& p, const std::vector<Axis>& axes, const ConfigOptions& base) {
  std::vector<std::string> args{"simulate", "--quiet", "--scene", p.scene, "--stats", p.stats_path};
  if (!base.config_path.empty()) args.insert(args.end(), {"--config", base.config_path});
  for (const auto& s : base.sets) args.insert(args.end(), {"--set", s});
  for (size_t i = 0; i < axes.size(); ++i) args.insert(args.end(), {"--set", axes[i].key + "=" + p.values[i]});
  return spawn_self(args, p.err_path);
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

// The cross product, scene-major; each point's stats and stderr files live in `tmp`.
std::vector<Point> make_points(const std::vector<std::string>& scenes, const std::vector<Axis>& axes,
                               const std::filesystem::path& tmp) {
  std::vector<Point> points;
  for (const auto& scene : scenes) {
    std::vector<size_t> idx(axes.size(), 0);
    for (;;) {
      Point p;
      p.scene = scene;
      for (size_t i = 0; i < axes.size(); ++i) p.values.push_back(axes[i].values[idx[i]]);
      const std::string n = std::to_string(points.size());
      p.stats_path = (tmp / (n + ".json")).string();
      p.err_path = (tmp / (n + ".err")).string();
      points.push_back(std::move(p));
      size_t i = axes.size();
      while (i > 0 && ++idx[i - 1] == axes[i - 1].values.size()) idx[--i] = 0;
      if (i == 0) break;
    }
  }
  return points;
}

// Runs every point, `jobs` child processes at once; returns how many failed.
size_t run_points(std::vector<Point>& points, const std::vector<Axis>& axes, const ConfigOptions& base,
                  unsigned jobs) {
  Progress progress(points.size());
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0, failed = 0;
  while (done < points.size()) {
    while (next < points.size() && running.size() < jobs) {
      running[spawn(points[next], axes, base)] = next;
      ++next;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) throw std::runtime_error("sweep: waitpid failed");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    Point& p = points[it->second];
    running.erase(it);
    ++done;
    p.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (p.status == 0) {
      std::ifstream is(p.stats_path);
      p.stats = nlohmann::json::parse(is);
    } else {
      ++failed;
      if (progress.tty()) std::cerr << "\n";
      std::cerr << "sweep: point " << describe(p, axes) << " failed: " << last_line(p.err_path) << "\n";
    }
    progress.update(done, failed, describe(p, axes) + (p.status == 0 ? " ok" : " FAILED"));
  }
  return failed;
}

// Columns: scene, swept keys, status, then every stat any successful run reported, in
// the order first seen (a method's own counters, e.g. scanline's pixels_wrong, appear
// only in its rows; the other rows leave them empty).
void write_csv(const std::string& out_path, const std::vector<Point>& points, const std::vector<Axis>& axes) {
  std::vector<std::string> stat_keys;
  std::set<std::string> seen{"scene"};
  for (const auto& p : points) {
    if (p.status != 0) continue;
    std::vector<std::pair<std::string, nlohmann::json>> flat;
    flatten(p.stats, "", flat);
    for (const auto& [k, v] : flat)
      if (seen.insert(k).second) stat_keys.push_back(k);
  }
  std::ofstream os(out_path);
  if (!os) throw std::runtime_error(out_path + ": cannot open for writing");
  os << "scene";
  for (const auto& a : axes) os << "," << csv_field(a.key);
  os << ",status";
  for (const auto& k : stat_keys) os << "," << csv_field(k);
  os << "\n";
  for (const auto& p : points) {
    os << csv_field(p.scene);
    for (const auto& v : p.values) os << "," << csv_field(v);
    os << "," << csv_field(p.status == 0 ? "ok" : last_line(p.err_path));
    std::map<std::string, nlohmann::json> flat_map;
    if (p.status == 0) {
      std::vector<std::pair<std::string, nlohmann::json>> flat;
      flatten(p.stats, "", flat);
      flat_map.insert(flat.begin(), flat.end());
    }
    for (const auto& k : stat_keys) os << "," << (flat_map.count(k) ? csv_value(flat_map[k]) : "");
    os << "\n";
  }
}

// `--area`: each point's RTL area (rastsim area, model/rtl/area.h) under "area" in its
// stats, so the CSV gains area.cells, area.flip_flops and area.transistors. Synthesised
// once a distinct RTL parameter set (a tile-size sweep over three scenes: one run a tile
// size), the rest from this map or the on-disk cache.
void add_area(std::vector<Point>& points, const std::vector<Axis>& axes, const ConfigOptions& base) {
  std::map<std::vector<std::pair<std::string, int>>, AreaReport> done;
  for (auto& p : points) {
    ConfigOptions c = base;
    for (size_t i = 0; i < axes.size(); ++i) c.sets.push_back(axes[i].key + "=" + p.values[i]);
    const RtlParams rp = rtl_params_from_config(load_config(c));
    const auto key = rtl_params_named(rp);
    auto it = done.find(key);
    if (it == done.end()) {
      AreaOptions ao;
      ao.progress = [&](const std::string& line) { std::cerr << "\r\033[Ksweep: area " << line << std::flush; };
      if (!isatty(2)) ao.progress = {};
      std::cerr << "sweep: area of " << describe(p, axes) << (isatty(2) ? "" : "\n");
      it = done.emplace(key, synthesize_area(rp, ao)).first;
      if (isatty(2)) std::cerr << "\r\033[K";
      std::cerr << "sweep: area " << (it->second.from_cache ? "from the cache" : "synthesised") << ": "
                << it->second.total.cells << " cells\n";
    }
    if (p.status != 0) continue;
    const AreaCounts& t = it->second.total;
    p.stats["area"] = {{"cells", t.cells}, {"flip_flops", t.flip_flops}, {"transistors", t.transistors}};
  }
}

}  // namespace

void run_sweep_command(SweepOptions o) {
  std::vector<Axis> axes = split_axes(o.set_args, o.base);
  validate_axes(load_config(o.base), axes);
  const auto tmp = std::filesystem::temp_directory_path() / ("rastsim-sweep-" + std::to_string(getpid()));
  std::filesystem::create_directories(tmp);
  std::vector<Point> points = make_points(o.scenes, axes, tmp);
  const size_t failed = run_points(points, axes, o.base, o.jobs);
  if (o.area) add_area(points, axes, o.base);
  write_csv(o.out_path, points, axes);
  std::filesystem::remove_all(tmp);
  std::cerr << "sweep: wrote " << points.size() << " rows to " << o.out_path << "\n";
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
  cmd->add_option("--out,-o", o.out_path, "CSV to write: scene, each swept key, then every stat")->required();
  cmd->add_flag("--area", o.area,
                "Add area.cells, area.flip_flops, area.transistors (rastsim area, Yosys; cached per RTL "
                "parameter set) to every row");
  cmd->add_option("--jobs,-j", o.jobs, "Simulations run at once (default: the number of cores)")
      ->check(CLI::Range(1u, 1024u));
  cmd->callback([] { run_sweep_command(o); });
}

}  // namespace rastsim::app
