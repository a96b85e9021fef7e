// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/area.h"

#include <csignal>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "rtlsim/rtl_cache.h"
#include "rtlsim/rtl_sources.h"
#include "util/hash.h"
#include "util/process.h"

namespace fs = std::filesystem;

namespace rastsim {

namespace {

// Bump when the method changes (script, JSON layout): old cache entries no longer match.
constexpr const char* kMethodVersion = "rastsim-area-2";  // 2: keys hash a module's own sources (area_sources_key)

// The Yosys script of one run (kRead, then kSynth). @DIR@ is the run's directory
// (sources, rast_params.vh), @WORK@ where this process writes (the run's directory, or a
// module's subdirectory in a split run), @FILES@ the sources, @ROOT@ the hierarchy's top (rast_top or rast_engine2d), @RETOP@
// empty or the lines that make one module under rast_top the top. A standalone root's
// parameters (AreaOptions::root_parameters) follow `hierarchy -top @ROOT@` (synth_run).
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
constexpr const char* kSynth = R"(synth -noabc -run begin:fine
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
tee -q -o @WORK@/stat.json stat -json -tech cmos
)";
constexpr const char* kRead = "read_verilog -sv -I@DIR@ @FILES@\nhierarchy -top @ROOT@\n";

// Split synthesis of a hierarchy (docs/area.md, "Method"), so no Yosys process holds the
// whole of rast_top:
// - kElaborate: elaborate once and list every derived module with the submodules it
//   instantiates (stat without -tech on the unsynthesised design: cells by type, the
//   submodule instances among them). No top at `stat`: see above.
//   It writes the elaborated design as RTLIL, which a module's run reads back in a tenth
//   of a second (elaborating again took 9 s on the smallest design).
// - kModule: read that, turn every other module into a blackbox (ports only), make
//   @MODULE@ the top and synthesise it alone with kSynth: its own gates, its submodule
//   instances left as cells of their (blackbox) types.
constexpr const char* kElaborate =
    "write_rtlil @DIR@/elaborated.il\nsetattr -mod -unset top *\ntee -q -o @WORK@/stat.json stat -json\n";
constexpr const char* kModule = "read_rtlil @DIR@/elaborated.il\nblackbox @OTHERS@\nsetattr -mod -unset top *\n"
                                "setattr -mod -set top 1 =@MODULE@\nhierarchy\n";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
  return s;
}

// An RTL source without its comments (line and block), for the instance scan below.
std::string without_comments(std::string_view text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const bool line = text.compare(i, 2, "//") == 0, block = text.compare(i, 2, "/*") == 0;
    if (!line && !block) {
      out += text[i];
      continue;
    }
    const size_t end = line ? text.find('\n', i) : text.find("*/", i + 2);
    if (end == std::string_view::npos) break;
    i = line ? end - 1 : end + 1;  // a line comment keeps its newline
  }
  return out;
}

// The instantiations in `text` (comments removed) of the modules in `modules`: (module,
// its parameter overrides "#(...)" with the blanks dropped, "" without any), one a site.
std::vector<std::pair<std::string, std::string>> instance_sites(const std::string& text,
                                                                const std::set<std::string>& modules) {
  static const std::regex site(R"(\b([a-z_][a-z0-9_]*)\s*(#\s*\()?)");
  static const std::regex instance_name(R"(^\s*[a-z_][a-z0-9_]*\s*\()");  // "u_fifo (": an instance
  std::vector<std::pair<std::string, std::string>> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), site); it != std::sregex_iterator(); ++it) {
    if (!modules.count((*it)[1].str())) continue;
    size_t pos = size_t(it->position(0) + it->length(0));
    std::string params;
    if ((*it)[2].matched)  // the balanced parentheses of the parameter list
      for (int depth = 1; pos < text.size() && depth > 0; ++pos) {
        depth += text[pos] == '(' ? 1 : text[pos] == ')' ? -1 : 0;
        if (depth > 0 && !std::isspace(static_cast<unsigned char>(text[pos]))) params += text[pos];
      }
    if (std::regex_search(text.begin() + std::ptrdiff_t(pos), text.end(), instance_name,
                          std::regex_constants::match_continuous))
      out.emplace_back((*it)[1].str(), params);
  }
  return out;
}

// `text` with its string literals emptied ("..." -> ""), so a name in a message is no use.
std::string without_strings(const std::string& text) {
  std::string out;
  bool in = false;
  for (size_t i = 0; i < text.size(); ++i) {
    if (in && text[i] == '\\') {
      ++i;  // an escaped character
      continue;
    }
    if (text[i] == '"') in = !in;
    if (!in || text[i] == '"') out += text[i];
  }
  return out;
}

// The files a module's synthesis reads (area_module_files): a graph of the sources by the
// names they declare (module, package, interface) and the names they use.
struct SourceGraph {
  std::map<std::string, size_t> declared;       // module/package/interface name -> source index
  std::vector<std::set<size_t>> uses;           // source -> the sources it instantiates, imports, includes

  explicit SourceGraph(const std::vector<RtlSource>& sources) : uses(sources.size()) {
    static const std::regex decl(R"(\b(module|package|interface)\s+(?:automatic\s+|static\s+)?([A-Za-z_][A-Za-z0-9_$]*))");
    static const std::regex pkg(R"(\b([A-Za-z_][A-Za-z0-9_]*)\s*::)");
    static const std::regex inc(R"re(`include\s+"([^"]+)")re");
    std::vector<std::string> code, bare;  // without comments; and without strings
    std::map<std::string, size_t> by_file;
    for (size_t k = 0; k < sources.size(); ++k) {
      code.push_back(without_comments(sources[k].text));
      bare.push_back(without_strings(code[k]));
      by_file[std::string(sources[k].name)] = k;
      for (auto it = std::sregex_iterator(bare[k].begin(), bare[k].end(), decl); it != std::sregex_iterator(); ++it)
        declared.emplace((*it)[2].str(), k);
    }
    std::set<std::string> names;
    for (const auto& [name, k] : declared) names.insert(name);
    for (size_t k = 0; k < sources.size(); ++k) {
      const auto use = [&](const std::string& name) {
        if (auto d = declared.find(name); d != declared.end() && d->second != k) uses[k].insert(d->second);
      };
      for (const auto& [module, params] : instance_sites(bare[k], names)) use(module);
      for (auto it = std::sregex_iterator(bare[k].begin(), bare[k].end(), pkg); it != std::sregex_iterator(); ++it)
        use((*it)[1].str());
      // `include of another source (rast_params.vh is generated: keyed by its text apart).
      for (auto it = std::sregex_iterator(code[k].begin(), code[k].end(), inc); it != std::sregex_iterator(); ++it)
        if (auto f = by_file.find((*it)[1].str()); f != by_file.end() && f->second != k) uses[k].insert(f->second);
    }
  }

  // The indices of `module`'s file and every file it reaches.
  std::set<size_t> closure(const std::string& module) const {
    const auto d = declared.find(module);
    if (d == declared.end()) throw std::runtime_error("area: no RTL source declares module " + module);
    std::set<size_t> seen{d->second};
    for (std::vector<size_t> todo{d->second}; !todo.empty();) {
      const size_t k = todo.back();
      todo.pop_back();
      for (size_t u : uses[k])
        if (seen.insert(u).second) todo.push_back(u);
    }
    return seen;
  }
};

// The embedded sources' graph, built once.
const SourceGraph& embedded_graph() {
  static const SourceGraph g(rtl_sources());
  return g;
}

std::string sources_key(const SourceGraph& g, const std::vector<RtlSource>& sources, const std::string& module) {
  Fnv64 h;
  for (size_t k : g.closure(module)) h.add(sources[k].name), h.add(sources[k].text);  // in name order (sorted sources)
  return h.hex();
}

}  // namespace

std::vector<std::string> area_module_files(const std::string& module, const std::vector<RtlSource>& sources) {
  const SourceGraph g(sources);
  std::vector<std::string> out;
  for (size_t k : g.closure(module)) out.emplace_back(sources[k].name);
  std::sort(out.begin(), out.end());
  return out;
}

std::string area_sources_key(const std::string& module, const std::vector<RtlSource>& sources) {
  return sources_key(SourceGraph(sources), sources, module);
}

namespace {

// Modules synthesised without synth's `share` pass (SAT-based resource sharing of
// mutually exclusive $mul, $shl, ... cells; docs/area.md "Method"): on the default config
// Yosys 0.23 had sat in `share` for more than 20 minutes on the interpolator and on
// rast_top's own logic (issue 28). Where both finish (embedded, raster.max_samples=2) the
// interpolator's own logic is the same netlist with and without it (111,080 gates,
// 859,316 transistors); without it the default's finishes (701,352 gates, 517 CPU s).
// Every other module keeps it (and its cache entries).
bool skips_share(const std::string& module) {
  return module == "rast_interpolate" || module == "rast_top";
}

// kSynth for a module (its base name), with synth -noshare for those above.
std::string synth_script(const std::string& module) {
  if (!skips_share(module)) return kSynth;
  return replace_all(kSynth, "synth -noabc -run begin:fine\n", "synth -noabc -noshare -run begin:fine\n");
}

// The synthesis of a one-process run: a stage alone (--top <module under rast_top>) as
// that module's; a root whole (rast_top --one-process, rast_engine2d, the units) kSynth.
std::string whole_synth_script(const std::string& stage) {
  return stage.empty() ? std::string(kSynth) : synth_script(stage);
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

// Modules Yosys keeps as blackboxes (`(* blackbox *)`), SRAM macros whose bits the caller
// counts as storage (area_memory.h): an instance adds no gate. The ROP cache's data array
// (also the texture cache's copies), the tile buffer's arrays and the fragment FIFO's ring
// of beats, by their base name (a derived "$paramod$<hash>\\rast_tile_buffer_data" too).
bool is_storage_blackbox(const std::string& type) {
  const std::string base = base_name(type);
  return base == "rast_rop_cache_data" || base == "rast_tile_buffer_data" || base == "rast_fragment_fifo_data";
}

// One module's entry of `stat -json [-tech cmos]`: its gates ($_*) as its own counts, the
// cell types is_module() names as submodule instances, storage blackboxes skipped; anything
// else is an error.
ModuleInfo module_from_stat(const std::string& id, const nlohmann::json& m,
                            const std::function<bool(const std::string&)>& is_module) {
  ModuleInfo info;
  if (m.contains("estimated_num_transistors")) info.own.transistors = transistors_of(m);
  for (const auto& [type, n] : m.at("num_cells_by_type").items()) {
    const uint64_t count = n.get<uint64_t>();
    // Yosys 0.23 gives an instance of a module without parameters its type without the
    // module id's leading backslash ("rast_fp32_unpack" for "\rast_fp32_unpack").
    const std::string child = is_module(type) ? type : is_module("\\" + type) ? "\\" + type : "";
    if (!child.empty()) {
      info.children.emplace_back(child, count);
      continue;
    }
    if (is_storage_blackbox(type)) continue;
    if (type.rfind("$_", 0) != 0)
      throw std::runtime_error("yosys stat: cell type " + type + " in " + id + " is neither a gate nor a module");
    info.own.cells_by_type[type] += count;
    info.own.cells += count;
    if (type == "$_DFF_P_" || type == "$_DFF_N_") info.own.flip_flops += count;
  }
  return info;
}

std::map<std::string, ModuleInfo> read_modules(const nlohmann::json& stat) {
  std::map<std::string, ModuleInfo> mods;
  const auto& modules = stat.at("modules");
  for (const auto& [id, m] : modules.items())
    mods[id] = module_from_stat(id, m, [&](const std::string& t) { return modules.contains(t); });
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

// What one Yosys process used, from its closing line ("CPU: user 1.2s system 0.1s, MEM:
// 95.3 MB peak").
struct YosysUsage {
  double cpu_seconds = 0;  // user + system
  double peak_mb = 0;      // peak resident memory, MB
  // Another process's usage: CPU summed, the larger peak (processes run side by side).
  void add(const YosysUsage& u) {
    cpu_seconds += u.cpu_seconds;
    peak_mb = std::max(peak_mb, u.peak_mb);
  }
};

// Runs Yosys on `script` in `dir`, reporting each pass of the top two levels ("16.6.
// Executing OPT pass") through `progress`; throws with Yosys' last lines on failure.
YosysUsage run_yosys(const std::string& yosys, const fs::path& dir, const std::string& label,
                     const std::function<void(const std::string&)>& progress) {
  static const std::regex pass_re(R"(^(\d+(\.\d+)?)\. Executing (\S+) pass)");
  static const std::regex usage_re(R"(CPU: user ([0-9.]+)s system ([0-9.]+)s, MEM: ([0-9.]+) MB peak)");
  YosysUsage usage;
  std::deque<std::string> tail;
  const auto t0 = std::chrono::steady_clock::now();
  ProcessOptions po;
  po.cwd = dir.string();
  po.out = Sink::Lines;
  po.err = Sink::Stdout;
  po.on_line = [&](const std::string& line) {
    std::smatch m;
    if (progress && std::regex_search(line, m, pass_re)) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::ostringstream os;
      os << label << ": " << m[1] << " " << m[3] << " (" << static_cast<int>(s) << " s)";
      progress(os.str());
    }
    if (std::regex_search(line, m, usage_re)) {
      usage.cpu_seconds = std::stod(m[1]) + std::stod(m[2]);
      usage.peak_mb = std::stod(m[3]);
    }
    tail.push_back(line);
    if (tail.size() > 8) tail.pop_front();
  };
  const int status = run_process({yosys, "-l", "yosys.log", "-s", "area.ys"}, po).status;
  if (status != 0) {
    std::string msg;
    for (const auto& l : tail)
      if (l.find("ERROR") != std::string::npos) msg = l;
    if (msg.empty() && !tail.empty()) msg = tail.back();
    // SIGKILL is most often the kernel's out-of-memory killer (rast_top of the wide
    // configs needs several GB).
    if (exit_code(status) == 128 + SIGKILL)
      msg = "killed (SIGKILL: out of memory? --jobs 1 runs one Yosys process at a time)";
    throw std::runtime_error("yosys failed on " + label + ": " + msg + " (log: " + (dir / "yosys.log").string() + ")");
  }
  return usage;
}

// The first line of `yosys -V`, "Yosys 0.23 (git sha1 ...)".
std::string yosys_version(const std::string& yosys) {
  ProcessOptions po;
  po.out = Sink::Capture;
  po.err = Sink::Stdout;
  std::string v = run_process({yosys, "-V"}, po).out;
  v = v.substr(0, v.find('\n'));
  while (!v.empty() && v.back() == '\r') v.pop_back();
  if (v.rfind("Yosys", 0) != 0) throw std::runtime_error(yosys + " -V did not print a Yosys version: " + v);
  return v;
}

// A run's directory in /tmp: every RTL source and the parameter header; removed with it.
struct RunDir {
  fs::path dir;
  std::string files;  // the sources, space-separated
  explicit RunDir(const std::string& params_vh) {
    char tmpl[] = "/tmp/rastsim-area-XXXXXX";
    if (!mkdtemp(tmpl)) throw std::runtime_error("cannot create a temporary directory in /tmp");
    dir = tmpl;
    for (const auto& s : rtl_sources()) {
      std::ofstream(dir / std::string(s.name)) << s.text;
      files += (files.empty() ? "" : " ") + (dir / std::string(s.name)).string();
    }
    std::ofstream(dir / "rast_params.vh") << params_vh;
  }
  ~RunDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  RunDir(const RunDir&) = delete;
  RunDir& operator=(const RunDir&) = delete;

  // Writes `script` (with @DIR@, @FILES@, @ROOT@ filled in), runs Yosys on it in `work`
  // (default: the run's directory) and returns the stat JSON it wrote there.
  nlohmann::json run(const std::string& yosys, std::string script, const std::string& root, const std::string& label,
                     const std::function<void(const std::string&)>& progress, YosysUsage& usage,
                     fs::path work = {}) const {
    if (work.empty()) work = dir;
    script = replace_all(replace_all(replace_all(script, "@FILES@", files), "@ROOT@", root), "@DIR@", dir.string());
    script = replace_all(script, "@WORK@", work.string());
    std::ofstream(work / "area.ys") << script;
    usage = run_yosys(yosys, work, label, progress);
    std::ifstream is(work / "stat.json");
    if (!is) throw std::runtime_error("yosys wrote no statistics for " + label + " (log: " + (work / "yosys.log").string() + ")");
    std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
    // Without a top module Yosys 0.23 ends the JSON with "},\n\n}": drop that comma.
    if (const size_t end = text.find_last_of('}'); end != std::string::npos && end > 0) {
      const size_t prev = text.find_last_not_of(" \t\r\n", end - 1);
      if (prev != std::string::npos && text[prev] == ',') text.erase(prev, 1);
    }
    return nlohmann::json::parse(text);
  }
};

// One synthesis run of a whole hierarchy in one process: `root` is the hierarchy's top;
// `stage` (optional) a module under it to synthesise alone, with the parameters rast_top
// gives it.
AreaReport synth_run(const std::string& yosys, const std::string& params_vh, const std::string& root,
                     const std::string& stage, const std::string& chparam, bool split_children,
                     const std::function<void(const std::string&)>& progress) {
  const RunDir run(params_vh);
  const std::string retop =
      stage.empty() ? "" : "setattr -mod -unset top " + root + "\nsetattr -mod -set top 1 *" + stage + "\nhierarchy\n";
  const std::string label = stage.empty() ? root : stage;
  YosysUsage usage;
  const std::string script = replace_all(replace_all(std::string(kRead) + "@RETOP@" + whole_synth_script(stage),
                                                   "@RETOP@", retop),
                                       "hierarchy -top @ROOT@\n", "hierarchy -top @ROOT@" + chparam + "\n");
  const nlohmann::json stat = run.run(yosys, script, root, label, progress, usage);
  AreaReport rep = area_from_yosys_stat(stat, label);
  if (!split_children) rep.stages = {{label, rep.total}};
  rep.cpu_seconds = usage.cpu_seconds;
  rep.peak_mb = usage.peak_mb;
  return rep;
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
  if (std::string p = find_program("yosys"); !p.empty()) return p;
  throw std::runtime_error(
      "yosys not found on PATH: area estimates need Yosys, Debian package `yosys` "
      "(apt-get install -y --no-install-recommends yosys; scripts/setup.sh installs it)");
}

namespace {

// Per-module totals of a hierarchy from each module's own gates and submodule instances
// (a stat JSON's modules, or the split runs' modules): see area_from_yosys_stat.
AreaReport area_from_modules(const std::map<std::string, ModuleInfo>& mods, const std::string& root) {
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

}  // namespace

AreaReport area_from_yosys_stat(const nlohmann::json& stat, const std::string& root) {
  return area_from_modules(read_modules(stat), root);
}

namespace {

nlohmann::json counts_json(const AreaCounts& c);
AreaCounts counts_from(const nlohmann::json& j);

// A cache entry: read (nullopt when absent or unreadable, which is said through
// `progress`), and written through a temporary file renamed into place, so a concurrent
// reader (a parallel sweep) never sees half a file.
std::optional<nlohmann::json> read_cache(const fs::path& file, const std::function<void(const std::string&)>& progress) {
  if (!fs::exists(file)) return std::nullopt;
  try {
    std::ifstream is(file);
    return nlohmann::json::parse(is);
  } catch (const std::exception& e) {
    if (progress) progress("cache entry " + file.string() + " unreadable (" + e.what() + "), synthesising");
    return std::nullopt;
  }
}

void write_cache(const fs::path& file, const nlohmann::json& j) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  const fs::path tmp = file.string() + ".tmp" + std::to_string(getpid()) + "-" +
                       std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
  std::ofstream os(tmp);
  os << j.dump(2) << "\n";
  os.close();
  if (os) fs::rename(tmp, file, ec);
  if (!os || ec) fs::remove(tmp, ec);
}

// What every cache key holds: the method, Yosys, and the RTL text `module`'s synthesis
// reads (area_sources_key: its file and those it reaches), so an edit elsewhere keeps
// the entry.
Fnv64 base_key(const std::string& yosys_version, const std::string& module) {
  Fnv64 h;
  h.add(kMethodVersion);
  h.add(yosys_version);
  h.add(sources_key(embedded_graph(), rtl_sources(), module));
  return h;
}

// Runs job(0) .. job(n - 1) on at most `workers` threads (each job one Yosys process);
// after a failure no further job starts, and the first failure is rethrown.
void run_jobs(size_t n, int workers, const std::function<void(size_t)>& job) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (size_t k; !failed && (k = next++) < n;) {
      try {
        job(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < std::min<int>(workers, static_cast<int>(n)); ++w) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

// One module of a split run as cached: its own gates, its submodule instances, what its
// Yosys process used.
struct ModuleRun {
  ModuleInfo info;
  double seconds = 0;
  YosysUsage usage;
  bool hit = false;
};

// rast_top split into one Yosys process a derived module (docs/area.md, "Method"):
// elaborate once for the module list, synthesise each module alone with its submodules
// as blackboxes (at most o.jobs processes at once), then sum own gates x instances up the
// hierarchy (area_from_modules). Each module is cached on its own: a derived module's
// name ($paramod...) holds every parameter it was built with, so its entry is keyed by
// the name and the sources and is shared by every config that derives the same module
// (a FIFO-depth sweep re-synthesises the FIFOs and rast_top's glue only). rast_top itself
// (not derived: it takes the header) is keyed with the header too.
class SplitSynthesis {
 public:
  SplitSynthesis(const std::string& yosys, const std::string& yosys_ver, const std::string& params_vh,
                 const std::string& root, const fs::path& cache_dir, const AreaOptions& o)
      : yosys_(yosys), yosys_ver_(yosys_ver), params_vh_(params_vh), root_(root), cache_dir_(cache_dir), o_(o) {}

  AreaReport run() {
    // 1. The derived modules and their submodule instances: from the cache, else by
    // elaborating (which also writes the RTLIL the modules' runs read).
    read_hierarchy();
    if (hierarchy_.empty()) elaborate();
    for (const auto& [id, children] : hierarchy_) ids_.push_back(id);
    // 2. Each module alone: the cached ones first, then one process a missing one.
    runs_.resize(ids_.size());
    for (size_t k = 0; k < ids_.size(); ++k)
      if (!read_module(k)) todo_.push_back(k);
    if (!todo_.empty()) {
      elaborate();  // the RTLIL (a cached module list came without it)
      if (hierarchy_.size() != ids_.size())
        throw std::runtime_error("yosys: " + root_ + " elaborated into other modules than the cached list");
      say(root_ + ": " + std::to_string(todo_.size()) + " of " + std::to_string(ids_.size()) +
          " modules to synthesise, one Yosys process each, " + std::to_string(o_.jobs) + " at a time");
    }
    run_jobs(todo_.size(), o_.jobs, [&](size_t t) { synthesise_module(todo_[t]); });
    // 3. The sums up the hierarchy.
    return sum();
  }

 private:
  void say(const std::string& line) {
    if (!o_.progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex_);
    o_.progress(line);
  }

  fs::path hierarchy_file() const {
    Fnv64 ek = base_key(yosys_ver_, root_);
    ek.add("elaborate");
    ek.add(kRead);
    ek.add(kElaborate);
    ek.add(root_);
    ek.add(params_vh_);
    return cache_dir_ / (ek.hex() + ".json");
  }

  void read_hierarchy() {
    if (auto j = o_.use_cache ? read_cache(hierarchy_file(), [&](const std::string& l) { say(l); }) : std::nullopt) {
      try {
        hierarchy_ = j->at("modules").get<decltype(hierarchy_)>();
      } catch (const std::exception&) {
        hierarchy_.clear();
      }
    }
  }

  // Elaborates rast_top once (the RTLIL stays in elab_ while modules need it) and lists
  // its derived modules with their submodule instances.
  void elaborate() {
    if (elab_) return;
    say(root_ + ": elaborating");
    elab_ = std::make_unique<RunDir>(params_vh_);
    YosysUsage usage;
    const nlohmann::json stat = elab_->run(yosys_, std::string(kRead) + kElaborate, root_, root_ + " (elaborate)",
                                           [&](const std::string& l) { say(l); }, usage);
    total_usage_.add(usage);
    const auto& modules = stat.at("modules");
    hierarchy_.clear();
    for (const auto& [id, m] : modules.items()) {
      auto& children = hierarchy_[id];
      for (const auto& [type, n] : m.at("num_cells_by_type").items())
        if (modules.contains(type)) children[type] += n.get<uint64_t>();
    }
    if (o_.use_cache) write_cache(hierarchy_file(), {{"root", root_}, {"modules", hierarchy_}});
  }

  fs::path module_file(const std::string& id) const {
    Fnv64 h = base_key(yosys_ver_, base_name(id));
    h.add("module");
    h.add(kRead);
    h.add(kElaborate);
    h.add(kModule);
    h.add(synth_script(base_name(id)));
    h.add(root_);
    h.add(id);
    h.add(id.rfind("$paramod", 0) == 0 ? "" : params_vh_);
    return cache_dir_ / (h.hex() + ".json");
  }

  // Module k from the cache; false when it is not there.
  bool read_module(size_t k) {
    ModuleRun& r = runs_[k];
    if (auto j = o_.use_cache ? read_cache(module_file(ids_[k]), [&](const std::string& l) { say(l); })
                              : std::nullopt) {
      try {
        r.info.own = counts_from(j->at("own"));
        r.info.children = j->at("children").get<std::vector<std::pair<std::string, uint64_t>>>();
        r.seconds = j->value("synth_seconds", 0.0);
        r.usage.cpu_seconds = j->value("cpu_seconds", 0.0);
        r.usage.peak_mb = j->value("peak_mb", 0.0);
        r.hit = true;
      } catch (const std::exception&) {
        r = ModuleRun{};
      }
    }
    return r.hit;
  }

  // Module k alone in its own Yosys process (on a worker thread), the others blackboxes.
  void synthesise_module(size_t k) {
    const std::string& id = ids_[k];
    ModuleRun& r = runs_[k];
    const std::string label = base_name(id) + " [" + std::to_string(k + 1) + "/" + std::to_string(ids_.size()) + "]";
    std::string others;
    for (const auto& other : ids_)
      if (other != id) others += (others.empty() ? "=" : " =") + other;
    const std::string script =
        replace_all(replace_all(std::string(kModule) + synth_script(base_name(id)), "@OTHERS@", others), "@MODULE@", id);
    const auto t1 = std::chrono::steady_clock::now();
    const fs::path work = elab_->dir / ("m" + std::to_string(k));
    fs::create_directories(work);
    const nlohmann::json stat = elab_->run(yosys_, script, root_, label, [&](const std::string& l) { say(l); },
                                           r.usage, work);
    const auto& modules = stat.at("modules");
    if (!modules.contains(id)) throw std::runtime_error("yosys stat: no module " + id + " after synthesising it alone");
    r.info = module_from_stat(id, modules.at(id), [&](const std::string& t) { return hierarchy_.count(t) > 0; });
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    if (o_.use_cache)
      write_cache(module_file(id), {{"module", id},
                                    {"own", counts_json(r.info.own)},
                                    {"children", r.info.children},
                                    {"synth_seconds", r.seconds},
                                    {"cpu_seconds", r.usage.cpu_seconds},
                                    {"peak_mb", r.usage.peak_mb}});
    std::ostringstream os;
    os << label << " synthesised (" << ++done_ << " of " << todo_.size() << ", " << static_cast<int>(r.seconds)
       << " s, " << static_cast<int>(r.usage.peak_mb) << " MB)";
    say(os.str());
  }

  AreaReport sum() {
    bool all_hit = true;
    std::map<std::string, ModuleInfo> mods;
    for (size_t k = 0; k < ids_.size(); ++k) {
      mods[ids_[k]] = runs_[k].info;
      all_hit = all_hit && runs_[k].hit && !elab_;
      total_usage_.add(runs_[k].usage);
    }
    AreaReport rep = area_from_modules(mods, root_);
    rep.modules = ids_.size();
    rep.from_cache = all_hit;
    rep.cpu_seconds = total_usage_.cpu_seconds;
    rep.peak_mb = total_usage_.peak_mb;
    rep.synth_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (all_hit) {
      rep.synth_seconds = 0;
      for (const ModuleRun& r : runs_) rep.synth_seconds += r.seconds;  // as cached: the runs' own times
    }
    return rep;
  }

  const std::string& yosys_;
  const std::string& yosys_ver_;
  const std::string& params_vh_;
  const std::string& root_;
  const fs::path& cache_dir_;
  const AreaOptions& o_;
  const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  std::mutex progress_mutex_;
  YosysUsage total_usage_;  // summed CPU, the largest process's peak
  std::map<std::string, std::map<std::string, uint64_t>> hierarchy_;  // module -> submodule -> instances
  std::unique_ptr<RunDir> elab_;  // the elaborated design, while modules need it
  std::vector<std::string> ids_;
  std::vector<ModuleRun> runs_;
  std::vector<size_t> todo_;  // indices of the modules to synthesise
  std::atomic<size_t> done_{0};
};

// Hierarchies synthesised apart from rast_top, each its own root: the 2D engine and the
// front end's binary32 units (docs/rtl.md, "Binary32 units of the front end"), with no
// config parameter, the reciprocal unit (docs/rtl.md, "Reciprocal unit") with the
// config's seed bits and iterations (root_rtl_params, AreaOptions::root_parameters);
// rast_top's interpolator holds its own at the config's, reported in the interpolator's
// rows; and the ROP's cache (docs/rtl.md, "ROP cache") with the colour cache's
// parameters, its data array a blackbox (rtl/rast_rop_cache_data.sv); the texture unit's
// units (docs/texture.md, "RTL"), the LOD and address units with the config's
// TextureRtlParams, the filter and the combine with none; the texture cache
// (rtl/rast_texture_cache.sv) with the config's, its data copies blackboxes; hierarchical
// Z's table and tile test (docs/rtl.md "Hi-Z"), with HizRtlParams.
const std::vector<std::string>& standalone_roots() {
  static const std::vector<std::string> roots{"rast_engine2d",        "rast_fp32_mul",        "rast_fp32_add",
                                              "rast_fp32_recip",      "rast_front_end_xform", "rast_recip",
                                              "rast_rop_cache",       "rast_texture_lod",     "rast_texture_address",
                                              "rast_texture_filter",  "rast_texture_combine", "rast_texture_cache",
                                              "rast_hiz",             "rast_hiz_test"};
  return roots;
}

bool is_standalone_root(const std::string& top) {
  const std::vector<std::string>& r = standalone_roots();
  return std::find(r.begin(), r.end(), top) != r.end();
}

}  // namespace

std::vector<std::string> area_reportable_tops() {
  // The instance graph of the embedded sources (one module a file, named by its stem).
  std::map<std::string, std::string> code;  // module -> source without comments
  std::set<std::string> modules;
  for (const auto& s : rtl_sources()) {
    const std::string stem(s.name.substr(0, s.name.rfind('.')));
    code[stem] = without_comments(s.text);
    modules.insert(stem);
  }
  std::map<std::string, std::set<std::string>> sets;  // module -> parameter texts of its sites under rast_top
  std::vector<std::string> todo{"rast_top"}, out{"rast_top"};
  out.insert(out.end(), standalone_roots().begin(), standalone_roots().end());
  std::set<std::string> seen{"rast_top"};
  while (!todo.empty()) {
    const std::string parent = todo.back();
    todo.pop_back();
    for (const auto& [module, params] : instance_sites(code[parent], modules)) {
      sets[module].insert(params);
      if (seen.insert(module).second) todo.push_back(module);
    }
  }
  // A module that every site instantiates with the same parameter text is one module in
  // Yosys' elaboration; several texts are several ("$paramod...\rast_fifo"), which one
  // report of one module cannot hold (the default report sums them in its row).
  for (const auto& [module, texts] : sets)
    if (texts.size() == 1 && !is_standalone_root(module)) out.push_back(module);
  return out;
}

namespace {

// --top must name a module the report can hold (area_reportable_tops), checked before
// Yosys runs; the error lists the choices.
void check_top(const std::string& top) {
  const std::vector<std::string> tops = area_reportable_tops();
  if (std::find(tops.begin(), tops.end(), top) != tops.end()) return;
  std::string names;
  for (const auto& t : tops) names += (names.empty() ? "" : ", ") + t;
  bool is_module = false;
  for (const auto& s : rtl_sources()) is_module |= s.name.substr(0, s.name.rfind('.')) == top;
  throw std::runtime_error("--top " + top + ": " +
                           (is_module ? "rast_top instantiates it with several parameter sets or not at all, and "
                                        "a report of one module holds one (the default report sums its instances "
                                        "in its row)"
                                      : "not an RTL module") +
                           "; --top takes " + names);
}

// One synthesis a part: the whole design is rast_top (split into its stages) and
// rast_engine2d; --top is one part. rast_top is synthesised a module a process
// (SplitSynthesis, o.split) or whole; rast_engine2d (small) and a stage under rast_top in
// one process each. rast_engine2d takes no config parameter, so one entry serves every
// config.
struct Part {
  std::string root, stage;
  bool split;
};

std::vector<Part> parts_of(const AreaOptions& o) {
  if (o.top.empty()) return {{"rast_top", "", true}, {"rast_engine2d", "", false}};
  if (o.top == "rast_top" || is_standalone_root(o.top)) return {{o.top, "", o.top == "rast_top"}};
  return {{"rast_top", o.top, false}};  // a module under rast_top, with the parameters rast_top derives
}

// " -chparam NAME VALUE" for each parameter, the arguments of Yosys' `hierarchy`.
std::string chparam_args(const std::vector<std::pair<std::string, int>>& params) {
  std::string out;
  for (const auto& [name, value] : params) out += " -chparam " + name + " " + std::to_string(value);
  return out;
}

// A part in one Yosys process, or from its cache entry (named `key`).
AreaReport synth_whole_part(const std::string& yosys, const std::string& yosys_ver, const std::string& params_vh,
                            const Part& part, const fs::path& dir, const AreaOptions& o, std::string& key) {
  Fnv64 h = base_key(yosys_ver, part.root);
  h.add(std::string(kRead) + "@RETOP@" + whole_synth_script(part.stage));
  h.add(part.root);
  h.add(part.stage);
  h.add(part.split ? "split" : "whole");
  h.add(part.root == "rast_top" ? params_vh : "");
  const std::string chparam = chparam_args(o.root_parameters);
  if (!chparam.empty()) h.add(chparam);  // none: the module's defaults, keyed as before parameters existed
  key = h.hex();
  const fs::path cache = dir / (key + ".json");
  AreaReport got;
  bool hit = false;
  if (auto j = o.use_cache ? read_cache(cache, o.progress) : std::nullopt) {
    try {
      got = area_from_json(*j);
      hit = true;
    } catch (const std::exception& e) {
      // An older entry: synthesise again and overwrite it.
      if (o.progress) o.progress("cache entry " + cache.string() + " unreadable (" + e.what() + "), synthesising");
    }
  }
  if (!hit) {
    const auto t0 = std::chrono::steady_clock::now();
    got = synth_run(yosys, params_vh, part.root, part.stage, chparam, part.split, o.progress);
    got.synth_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    got.yosys_version = yosys_ver;
    got.top = part.stage.empty() ? part.root : part.stage;
    got.key = key;
    got.modules = 1;
    if (o.use_cache) write_cache(cache, area_to_json(got));
  }
  got.from_cache = hit;
  return got;
}

// rast_top a module a process (SplitSynthesis); `key` names the split run.
AreaReport synth_split_part(const std::string& yosys, const std::string& yosys_ver, const std::string& params_vh,
                            const Part& part, const fs::path& dir, const AreaOptions& o, std::string& key) {
  AreaReport got = SplitSynthesis(yosys, yosys_ver, params_vh, part.root, dir, o).run();
  Fnv64 h = base_key(yosys_ver, part.root);
  h.add("split");
  h.add(params_vh);
  key = h.hex();
  return got;
}

// Adds a part's figures to the whole report.
void add_part(AreaReport& r, const AreaReport& got) {
  r.from_cache = r.from_cache && got.from_cache;
  r.synth_seconds += got.synth_seconds;
  r.cpu_seconds += got.cpu_seconds;
  r.peak_mb = std::max(r.peak_mb, got.peak_mb);
  r.modules += got.modules;
  for (const auto& [name, c] : got.stages) r.stages[name] = c;
  r.total += got.total;
}

}  // namespace

AreaReport synthesize_area(const RtlParams& p, const AreaOptions& o) {
  if (!o.top.empty()) check_top(o.top);
  const std::vector<std::string> takes = root_rtl_param_names(o.top);
  for (const auto& [name, value] : o.root_parameters)
    if (std::find(takes.begin(), takes.end(), name) == takes.end())
      throw std::runtime_error("area: " + (o.top.empty() ? std::string("the whole design") : o.top) +
                               " takes no parameter " + name + " from the config (a standalone root's parameters: "
                               "rast_recip's SEED_BITS and ITERATIONS, rast_rop_cache's AddrW, CacheBytes, Ways, "
                               "LineBytes and WordBytes, rast_texture_lod's and rast_texture_address's "
                               "TexW, TexFrac, SizeW and LevelW, BiasW or WeightBits, AddrW; rast_texture_cache's "
                               "AddrW, CacheBytes, Ways, LineBytes, Ports and BeatBytes; rast_hiz's and "
                               "rast_hiz_test's HizRtlParams fields)");
  if (o.jobs < 1) throw std::runtime_error("area: jobs must be at least 1, not " + std::to_string(o.jobs));
  const std::string yosys = find_yosys();
  AreaReport r;
  r.top = o.top;
  r.parameters = o.root_parameters.empty() ? rtl_params_named(p) : o.root_parameters;
  r.yosys_version = yosys_version(yosys);
  // The header's banner names no file, so two configs with the same parameters share a key.
  const std::string params_vh = rtl_params_verilog(p, "rastsim area");
  const std::vector<Part> parts = parts_of(o);
  const fs::path dir = o.cache_dir.empty() ? area_cache_dir() : o.cache_dir;
  Fnv64 whole;
  std::string key;
  r.from_cache = true;
  r.total.instances = 0;
  for (const Part& part : parts) {
    const auto synth = part.root == "rast_top" && part.stage.empty() && o.split ? synth_split_part : synth_whole_part;
    add_part(r, synth(yosys, r.yosys_version, params_vh, part, dir, o, key));
    whole.add(key);
  }
  r.total.instances = 1;
  r.key = parts.size() == 1 ? key : whole.hex();  // one part: its cache file's name
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
  nlohmann::json storage = nlohmann::json::array();
  for (const StorageArray& a : r.storage)
    storage.push_back({{"name", a.name}, {"bits", a.bits}, {"kind", a.sram ? "sram" : "flip_flops"},
                       {"transistors", a.transistors}});
  j["storage"] = storage;
  j["top"] = r.top.empty() ? "rast_top+rast_engine2d" : r.top;
  j["yosys"] = r.yosys_version;
  j["key"] = r.key;
  j["synth_seconds"] = r.synth_seconds;
  j["synth_cpu_seconds"] = r.cpu_seconds;
  j["synth_peak_mb"] = r.peak_mb;
  j["yosys_processes"] = r.modules;
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
  for (const auto& a : j.value("storage", nlohmann::json::array()))
    r.storage.push_back({a.at("name").get<std::string>(), a.at("bits").get<uint64_t>(),
                         a.at("kind").get<std::string>() == "sram", a.at("transistors").get<uint64_t>()});
  const std::string top = j.value("top", "");
  r.top = top == "rast_top+rast_engine2d" ? "" : top;
  r.yosys_version = j.value("yosys", "");
  r.key = j.value("key", "");
  r.synth_seconds = j.value("synth_seconds", 0.0);
  r.cpu_seconds = j.value("synth_cpu_seconds", 0.0);
  r.peak_mb = j.value("synth_peak_mb", 0.0);
  r.modules = j.value("yosys_processes", 0);
  r.from_cache = j.value("from_cache", false);
  // Params as written (nlohmann's object is sorted by name, not in table order).
  const nlohmann::json params = j.value("parameters", nlohmann::json::object());
  for (const auto& [k, v] : params.items()) r.parameters.emplace_back(k, v.get<int>());
  return r;
}

}  // namespace rastsim
