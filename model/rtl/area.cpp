// SPDX-License-Identifier: Apache-2.0
#include "rtl/area.h"

#include <sys/wait.h>
#include <csignal>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "rtl/rtl_cache.h"
#include "rtl/rtl_sources.h"

namespace fs = std::filesystem;

namespace rastsim {

namespace {

// Bump when the method changes (script, JSON layout): old cache entries no longer match.
constexpr const char* kMethodVersion = "rastsim-area-1";

// The Yosys script of one run. @DIR@ is the run's directory (sources, rast_params.vh),
// @FILES@ the sources, @ROOT@ the hierarchy's top (rast_top or rast_engine2d), @RETOP@
// empty or the lines that make one module under rast_top the top.
// - synth's coarse steps (proc, fsm, wreduce, alumacc, share, memory), hierarchy kept
//   for the per-module stat; then its fine steps with `opt -fast` where synth runs
//   `opt -full` after memory_map: on rast_top that loop alone ran over 10 CPU minutes
//   (hundreds of opt_expr rounds shaving a few cells each), abc cleans up the same.
// - async2sync + dfflegalize: every flop a plain positive-edge D flop, its asynchronous
//   reset and enable turned into gates, because `stat -tech cmos` prices only $_DFF_P_/N_.
// - abc -fast: logic optimisation in seconds (plain abc takes minutes on the multipliers).
// - No top module at `stat`: with one, Yosys 0.23 appends its "design hierarchy" listing,
//   whose lines below the second level land unquoted inside the JSON. The per-module
//   totals are summed here (area_from_yosys_stat) instead. (Without a top it leaves a
//   trailing comma, removed before parsing.)
constexpr const char* kScript = R"(read_verilog -sv -I@DIR@ @FILES@
hierarchy -top @ROOT@
@RETOP@synth -noabc -run begin:fine
opt -fast -full
memory_map
opt -fast
techmap
opt -fast
async2sync
dfflegalize -cell $_DFF_P_ 01
abc -fast
opt -fast
opt_clean
setattr -mod -unset top *
tee -q -o @DIR@/stat.json stat -json -tech cmos
)";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
  return s;
}

// "$paramod$<sha1>\rast_fifo", "$paramod\rast_hold\Width=..." and "\rast_top" -> the module's name.
std::string base_name(const std::string& id) {
  if (id.rfind("$paramod", 0) == 0) {
    const size_t a = id.find('\\');
    if (a == std::string::npos) return id;
    const size_t b = id.find('\\', a + 1);
    return id.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
  }
  return (!id.empty() && id[0] == '\\') ? id.substr(1) : id;
}

uint64_t transistors_of(const nlohmann::json& m) {
  const auto& t = m.at("estimated_num_transistors");
  if (t.is_number()) return t.get<uint64_t>();
  // A string, with a trailing '+' when the module instantiates cells stat cannot price
  // (submodules: added below from their own totals).
  return std::stoull(t.get<std::string>());
}

struct ModuleInfo {
  AreaCounts own;                                   // its gates, no submodules
  std::vector<std::pair<std::string, uint64_t>> children;  // submodule id, instances
};

std::map<std::string, ModuleInfo> read_modules(const nlohmann::json& stat) {
  std::map<std::string, ModuleInfo> mods;
  const auto& modules = stat.at("modules");
  for (const auto& [id, m] : modules.items()) {
    ModuleInfo info;
    info.own.transistors = transistors_of(m);
    for (const auto& [type, n] : m.at("num_cells_by_type").items()) {
      const uint64_t count = n.get<uint64_t>();
      if (modules.contains(type)) {
        info.children.emplace_back(type, count);
        continue;
      }
      if (type.rfind("$_", 0) != 0)
        throw std::runtime_error("yosys stat: cell type " + type + " in " + id + " is neither a gate nor a module");
      info.own.cells_by_type[type] += count;
      info.own.cells += count;
      if (type == "$_DFF_P_" || type == "$_DFF_N_") info.own.flip_flops += count;
    }
    mods[id] = std::move(info);
  }
  return mods;
}

AreaCounts total_of(const std::string& id, const std::map<std::string, ModuleInfo>& mods,
                    std::map<std::string, AreaCounts>& memo) {
  if (auto it = memo.find(id); it != memo.end()) return it->second;
  const ModuleInfo& m = mods.at(id);
  AreaCounts t = m.own;
  for (const auto& [child, n] : m.children) {
    const AreaCounts c = total_of(child, mods, memo);
    for (uint64_t k = 0; k < n; ++k) t += c;
  }
  t.instances = 1;
  return memo[id] = t;
}

// Runs Yosys on `script` in `dir`, reporting each pass of the top two levels ("16.6.
// Executing OPT pass") through `progress`; throws with Yosys' last lines on failure.
void run_yosys(const std::string& yosys, const fs::path& dir, const std::string& label,
               const std::function<void(const std::string&)>& progress) {
  const std::string cmd = "cd '" + dir.string() + "' && '" + yosys + "' -l yosys.log -s area.ys 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot start " + yosys);
  static const std::regex pass_re(R"(^(\d+(\.\d+)?)\. Executing (\S+) pass)");
  std::deque<std::string> tail;
  const auto t0 = std::chrono::steady_clock::now();
  char buf[4096];
  std::string line;
  while (std::fgets(buf, sizeof buf, pipe)) {
    line += buf;
    if (line.back() != '\n') continue;
    line.pop_back();
    std::smatch m;
    if (progress && std::regex_search(line, m, pass_re)) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::ostringstream os;
      os << label << ": " << m[1] << " " << m[3] << " (" << static_cast<int>(s) << " s)";
      progress(os.str());
    }
    tail.push_back(line);
    if (tail.size() > 8) tail.pop_front();
    line.clear();
  }
  const int status = pclose(pipe);
  if (status != 0) {
    std::string msg;
    for (const auto& l : tail)
      if (l.find("ERROR") != std::string::npos) msg = l;
    if (msg.empty() && !tail.empty()) msg = tail.back();
    // The shell reports a killed child as 128 + signal: SIGKILL is most often the
    // kernel's out-of-memory killer (rast_top of the wide configs needs several GB).
    if (WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGKILL)
      msg = "killed (SIGKILL: out of memory? try --top with one stage module)";
    throw std::runtime_error("yosys failed on " + label + ": " + msg + " (log: " + (dir / "yosys.log").string() + ")");
  }
}

std::string yosys_version(const std::string& yosys) {
  FILE* pipe = popen(("'" + yosys + "' -V 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot start " + yosys);
  char buf[256] = {0};
  std::string v = std::fgets(buf, sizeof buf, pipe) ? buf : "";
  pclose(pipe);
  while (!v.empty() && (v.back() == '\n' || v.back() == '\r')) v.pop_back();
  if (v.rfind("Yosys", 0) != 0) throw std::runtime_error(yosys + " -V did not print a Yosys version: " + v);
  return v;
}

// One synthesis run: `root` is the hierarchy's top; `stage` (optional) a module under it
// to synthesise alone, with the parameters rast_top gives it.
AreaReport synth_run(const std::string& yosys, const std::string& params_vh, const std::string& root,
                     const std::string& stage, bool split_children,
                     const std::function<void(const std::string&)>& progress) {
  char tmpl[] = "/tmp/rastsim-area-XXXXXX";
  if (!mkdtemp(tmpl)) throw std::runtime_error("cannot create a temporary directory in /tmp");
  const fs::path dir = tmpl;
  std::string files;
  for (const auto& s : rtl_sources()) {
    std::ofstream(dir / std::string(s.name)) << s.text;
    files += (files.empty() ? "" : " ") + (dir / std::string(s.name)).string();
  }
  std::ofstream(dir / "rast_params.vh") << params_vh;
  const std::string retop =
      stage.empty() ? "" : "setattr -mod -unset top " + root + "\nsetattr -mod -set top 1 *" + stage + "\nhierarchy\n";
  std::string script = replace_all(kScript, "@DIR@", dir.string());
  script = replace_all(replace_all(replace_all(script, "@FILES@", files), "@ROOT@", root), "@RETOP@", retop);
  std::ofstream(dir / "area.ys") << script;
  const std::string label = stage.empty() ? root : stage;
  run_yosys(yosys, dir, label, progress);
  std::ifstream is(dir / "stat.json");
  if (!is) throw std::runtime_error("yosys wrote no statistics for " + label + " (log: " + (dir / "yosys.log").string() + ")");
  const AreaReport r = [&] {
    std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
    // Without a top module Yosys 0.23 ends the JSON with "},\n\n}": drop that comma.
    if (const size_t end = text.find_last_of('}'); end != std::string::npos && end > 0) {
      const size_t prev = text.find_last_not_of(" \t\r\n", end - 1);
      if (prev != std::string::npos && text[prev] == ',') text.erase(prev, 1);
    }
    const nlohmann::json stat = nlohmann::json::parse(text);
    AreaReport rep = area_from_yosys_stat(stat, label);
    if (!split_children) rep.stages = {{label, rep.total}};
    return rep;
  }();
  fs::remove_all(dir);
  return r;
}

}  // namespace

AreaCounts& AreaCounts::operator+=(const AreaCounts& o) {
  cells += o.cells;
  flip_flops += o.flip_flops;
  transistors += o.transistors;
  instances += o.instances;
  for (const auto& [k, v] : o.cells_by_type) cells_by_type[k] += v;
  return *this;
}

std::string area_cache_dir() { return rastsim_cache_dir("area"); }

std::string find_yosys() {
  if (const char* y = std::getenv("RASTSIM_YOSYS"); y && *y) {
    if (access(y, X_OK) != 0)
      throw std::runtime_error(std::string("RASTSIM_YOSYS=") + y + " is not an executable (Yosys: Debian package yosys)");
    return y;
  }
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  for (std::string d; std::getline(ss, d, ':');) {
    const fs::path p = fs::path(d.empty() ? "." : d) / "yosys";
    if (access(p.c_str(), X_OK) == 0) return p.string();
  }
  throw std::runtime_error(
      "yosys not found on PATH: area estimates need Yosys, Debian package `yosys` "
      "(apt-get install -y --no-install-recommends yosys; scripts/setup.sh installs it)");
}

AreaReport area_from_yosys_stat(const nlohmann::json& stat, const std::string& root) {
  const auto mods = read_modules(stat);
  std::string root_id;
  for (const auto& [id, m] : mods)
    if (base_name(id) == root) {
      if (!root_id.empty()) throw std::runtime_error("yosys stat: several modules named " + root);
      root_id = id;
    }
  if (root_id.empty()) throw std::runtime_error("yosys stat: no module " + root + " in the synthesised design");
  std::map<std::string, AreaCounts> memo;
  AreaReport r;
  r.total = total_of(root_id, mods, memo);
  // The root's children, grouped by module (several FIFOs: one entry, instances summed),
  // and the root's own gates.
  const ModuleInfo& top = mods.at(root_id);
  for (const auto& [child, n] : top.children) {
    const AreaCounts c = total_of(child, mods, memo);
    const std::string name = base_name(child);
    for (uint64_t k = 0; k < n; ++k) {
      auto [it, fresh] = r.stages.try_emplace(name, c);
      if (!fresh) it->second += c;
    }
  }
  if (!top.children.empty()) {
    AreaCounts glue = top.own;
    glue.instances = 1;
    r.stages[root + "_glue"] = glue;
  } else {
    r.stages[root] = r.total;
  }
  return r;
}

AreaReport synthesize_area(const RtlParams& p, const AreaOptions& o) {
  static const std::vector<std::string> kRoots = {"rast_top", "rast_engine2d"};
  if (!o.top.empty()) {
    bool known = false;
    std::string names;
    for (const auto& s : rtl_sources()) {
      const std::string stem(s.name.substr(0, s.name.rfind('.')));
      known |= stem == o.top;
      names += (names.empty() ? "" : ", ") + stem;
    }
    if (!known) throw std::runtime_error("--top " + o.top + ": not an RTL module (" + names + ")");
  }
  const std::string yosys = find_yosys();
  AreaReport r;
  r.top = o.top;
  r.parameters = rtl_params_named(p);
  r.yosys_version = yosys_version(yosys);
  // The header's banner names no file, so two configs with the same parameters share a key.
  const std::string params_vh = rtl_params_verilog(p, "rastsim area");

  // One synthesis a part: the whole design is rast_top (split into its stages) and
  // rast_engine2d; --top is one part. Each part is cached on its own under a hash of what
  // decides it; rast_engine2d takes no config parameter, so one entry serves every config.
  struct Part {
    std::string root, stage;
    bool split;
  };
  std::vector<Part> parts;
  if (o.top.empty()) parts = {{"rast_top", "", true}, {"rast_engine2d", "", false}};
  else if (o.top == "rast_top" || o.top == "rast_engine2d") parts = {{o.top, "", o.top == "rast_top"}};
  else parts = {{"rast_top", o.top, false}};  // a module under rast_top, with the parameters rast_top derives

  const fs::path dir = o.cache_dir.empty() ? area_cache_dir() : o.cache_dir;
  Fnv64 whole;
  std::string last_key;
  r.from_cache = true;
  r.total.instances = 0;
  for (const Part& part : parts) {
    Fnv64 h;
    h.add(kMethodVersion);
    h.add(r.yosys_version);
    h.add(kScript);
    h.add(part.root);
    h.add(part.stage);
    h.add(part.split ? "split" : "whole");
    h.add(part.root == "rast_top" ? params_vh : "");
    for (const auto& s : rtl_sources()) h.add(s.name), h.add(s.text);
    whole.add(h.hex());
    last_key = h.hex();
    const fs::path cache = dir / (h.hex() + ".json");

    AreaReport got;
    bool hit = false;
    if (o.use_cache && fs::exists(cache)) {
      try {
        std::ifstream is(cache);
        got = area_from_json(nlohmann::json::parse(is));
        hit = true;
      } catch (const std::exception& e) {
        // A truncated or older entry: synthesise again and overwrite it.
        if (o.progress) o.progress("cache entry " + cache.string() + " unreadable (" + e.what() + "), synthesising");
      }
    }
    if (!hit) {
      const auto t0 = std::chrono::steady_clock::now();
      got = synth_run(yosys, params_vh, part.root, part.stage, part.split, o.progress);
      got.synth_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      got.yosys_version = r.yosys_version;
      got.top = part.stage.empty() ? part.root : part.stage;
      got.key = h.hex();
      if (o.use_cache) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        const fs::path tmp = cache.string() + ".tmp" + std::to_string(getpid());
        std::ofstream os(tmp);
        os << area_to_json(got).dump(2) << "\n";
        os.close();
        // Renamed into place, so a concurrent reader (a parallel sweep) never sees half a file.
        if (os) fs::rename(tmp, cache, ec);
        if (!os || ec) fs::remove(tmp, ec);
      }
    }
    r.from_cache = r.from_cache && hit;
    r.synth_seconds += got.synth_seconds;
    for (const auto& [name, c] : got.stages) r.stages[name] = c;
    r.total += got.total;
  }
  r.total.instances = 1;
  r.key = parts.size() == 1 ? last_key : whole.hex();  // one part: its cache file's name
  return r;
}

namespace {

nlohmann::json counts_json(const AreaCounts& c) {
  return {{"cells", c.cells}, {"flip_flops", c.flip_flops}, {"transistors", c.transistors},
          {"instances", c.instances}, {"cells_by_type", c.cells_by_type}};
}

AreaCounts counts_from(const nlohmann::json& j) {
  AreaCounts c;
  c.cells = j.at("cells").get<uint64_t>();
  c.flip_flops = j.at("flip_flops").get<uint64_t>();
  c.transistors = j.at("transistors").get<uint64_t>();
  c.instances = j.value("instances", uint64_t{1});
  c.cells_by_type = j.at("cells_by_type").get<std::map<std::string, uint64_t>>();
  return c;
}

}  // namespace

nlohmann::json area_to_json(const AreaReport& r) {
  nlohmann::json j = {{"cells", r.total.cells},
                      {"flip_flops", r.total.flip_flops},
                      {"transistors", r.total.transistors},
                      {"cells_by_type", r.total.cells_by_type}};
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, c] : r.stages) stages[name] = counts_json(c);
  j["stages"] = stages;
  j["top"] = r.top.empty() ? "rast_top+rast_engine2d" : r.top;
  j["yosys"] = r.yosys_version;
  j["key"] = r.key;
  j["synth_seconds"] = r.synth_seconds;
  j["from_cache"] = r.from_cache;
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : r.parameters) params[k] = v;
  j["parameters"] = params;
  return j;
}

AreaReport area_from_json(const nlohmann::json& j) {
  AreaReport r;
  r.total = counts_from(j);
  for (const auto& [name, s] : j.at("stages").items()) r.stages[name] = counts_from(s);
  const std::string top = j.value("top", "");
  r.top = top == "rast_top+rast_engine2d" ? "" : top;
  r.yosys_version = j.value("yosys", "");
  r.key = j.value("key", "");
  r.synth_seconds = j.value("synth_seconds", 0.0);
  r.from_cache = j.value("from_cache", false);
  // Params as written (nlohmann's object is sorted by name, not in table order).
  const nlohmann::json params = j.value("parameters", nlohmann::json::object());
  for (const auto& [k, v] : params.items()) r.parameters.emplace_back(k, v.get<int>());
  return r;
}

}  // namespace rastsim
