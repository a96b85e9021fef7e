// SPDX-License-Identifier: Apache-2.0
#include "common.h"
#include "scene/scene_io.h"
#include "scene/scene_params.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "util/hash.h"
#include "util/atomic_file.h"
#include "util/process.h"
#include "util/version.h"

namespace rastsim::app {

namespace {

// FNV-1a 64 of a file's bytes, read a MiB at a time: scenes reach hundreds of MB.
std::string file_hash(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw std::runtime_error(path + ": cannot open to hash it");
  std::vector<char> block(size_t{1} << 20);
  uint64_t h = kFnv64OffsetBasis;
  while (is.read(block.data(), std::streamsize(block.size())) || is.gcount() > 0)
    h = fnv1a64({block.data(), size_t(is.gcount())}, h);
  if (is.bad()) throw std::runtime_error(path + ": read failed while hashing it");
  return hex64(h);
}

}  // namespace

nlohmann::json provenance(const ConfigOptions& o, const Config& resolved, const std::string& scene_path) {
  const auto path_or_null = [](const std::string& p) { return p.empty() ? nlohmann::json() : nlohmann::json(p); };
  return {{"rastsim_version", rastsim_version()},
          {"argv", this_command_line()},
          {"cwd", std::filesystem::current_path().string()},
          {"config_path", path_or_null(o.config_path)},
          {"sets", o.sets},
          {"config_toml", config_toml(resolved)},
          {"config_hash", config_hash(resolved)},
          {"scene_path", path_or_null(scene_path)},
          {"scene_hash", scene_path.empty() ? nlohmann::json() : nlohmann::json(file_hash(scene_path))}};
}

void add_scene_option(CLI::App* cmd, std::string& scene_path) {
  cmd->add_option("--scene,-s", scene_path,
                  "Scene: a trace (.trace, docs/trace-format.md) or a Wavefront OBJ (.obj), either gzip- or "
                  "zstd-compressed too (.gz, .zst)")
      ->required()
      ->check(CLI::ExistingFile);
}

void add_config_options(CLI::App* cmd, ConfigOptions& o) {
  cmd->add_option("--config,-c", o.config_path,
                  "Architecture config (TOML); keys not in the file keep their defaults "
                  "(`rastsim config --doc` lists them)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", o.sets,
                  "Override one config key, e.g. --set raster.tile_size=32 (repeatable; "
                  "applied after --config, in order)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

Config load_config(const ConfigOptions& o) {
  Config cfg;
  if (!o.config_path.empty()) cfg.load_file(o.config_path);
  for (const auto& s : o.sets) cfg.apply_override(s);
  cfg.validate();
  return cfg;
}

ArchParams resolve_arch(const ConfigOptions& o) { return ArchParams::resolve(load_config(o)); }
ArchParams resolve_arch(const ConfigOptions& o, const std::string& scene_path) {
  return resolve_for_scene(load_config(o), scene_path);
}

void write_json(const std::string& path, const nlohmann::json& j) {
  if (path == "-") {
    std::cout << j.dump(2) << "\n";
    return;
  }
  AtomicFile f(path);
  f.stream() << j.dump(2) << "\n";
  f.commit();
}

std::ostream& summary_stream(const std::string& stats_path, bool quiet) {
  static std::ostream nowhere(nullptr);  // no buffer: every write is dropped
  if (quiet) return nowhere;
  return stats_path == "-" ? std::cerr : std::cout;
}

void add_quiet_flag(CLI::App* cmd, bool& quiet, const std::string& what) {
  cmd->add_flag("--quiet,-q", quiet, "Do not print " + what + " (errors still print; every output named is written)");
}

void check_one_stdout(const std::vector<std::pair<std::string, std::string>>& option_paths) {
  std::string first;
  for (const auto& [option, path] : option_paths) {
    if (path != "-") continue;
    if (!first.empty())
      throw std::runtime_error(first + " and " + option + " both write to stdout: at most one output can go there");
    first = option;
  }
}

nlohmann::json simulate_in_child(const ConfigOptions& o, const std::string& scene,
                                 const std::vector<std::string>& extra) {
  const TempDir dir("rastsim-sim");
  const std::string stats = dir.file("stats.json"), err = dir.file("stderr");
  std::vector<std::string> args{"simulate", "--quiet", "--scene", scene, "--stats", stats};
  args.insert(args.end(), extra.begin(), extra.end());
  if (!o.config_path.empty()) args.insert(args.end(), {"--config", o.config_path});
  for (const auto& s : o.sets) args.insert(args.end(), {"--set", s});
  nlohmann::json j;
  const bool ok = run_self(args, worker_options(err)).ok();
  const std::string why = ok ? "" : last_line(err);
  if (ok) j = nlohmann::json::parse(std::ifstream(stats));
  if (!ok) throw std::runtime_error("timed raster run failed: " + why);
  return j;
}

}  // namespace rastsim::app
