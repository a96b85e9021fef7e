// SPDX-License-Identifier: Apache-2.0
#include "common.h"
#include "scene/scene_io.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "util/atomic_file.h"
#include "util/process.h"

namespace rastsim::app {

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

void write_json(const std::string& path, const nlohmann::json& j) {
  if (path == "-") {
    std::cout << j.dump(2) << "\n";
    return;
  }
  AtomicFile f(path);
  f.stream() << j.dump(2) << "\n";
  f.commit();
}

nlohmann::json simulate_in_child(const ConfigOptions& o, const std::string& scene) {
  const TempDir dir("rastsim-sim");
  const std::string stats = dir.file("stats.json"), err = dir.file("stderr");
  std::vector<std::string> args{"simulate", "--quiet", "--scene", scene, "--stats", stats};
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
