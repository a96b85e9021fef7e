// SPDX-License-Identifier: Apache-2.0
#include "common.h"
#include "scene/scene_io.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include <fstream>
#include <iostream>

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
  std::ofstream os(path);
  if (!os) throw std::runtime_error(path + ": cannot open for writing");
  os << j.dump(2) << "\n";
  if (!os) throw std::runtime_error(path + ": write failed");
}

pid_t spawn_self(const std::vector<std::string>& args, const std::string& err_path) {
  std::vector<std::string> argv_s{"rastsim"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid != 0) return pid;
  // The child ends with its parent (a killed sweep leaves no simulations running on).
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (getppid() != parent) _exit(1);
  const int null_fd = open("/dev/null", O_WRONLY);
  const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (null_fd >= 0) dup2(null_fd, 1);
  if (err_fd >= 0) dup2(err_fd, 2);
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv("/proc/self/exe", argv.data());
  _exit(127);
}

std::string last_line(const std::string& path) {
  std::ifstream is(path);
  std::string line, last;
  while (std::getline(is, line))
    if (!line.empty()) last = line;
  return last.empty() ? "(no message)" : last;
}

nlohmann::json simulate_in_child(const ConfigOptions& o, const std::string& scene) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("rastsim-sim-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string stats = (dir / "stats.json").string(), err = (dir / "stderr").string();
  std::vector<std::string> args{"simulate", "--quiet", "--scene", scene, "--stats", stats};
  if (!o.config_path.empty()) args.insert(args.end(), {"--config", o.config_path});
  for (const auto& s : o.sets) args.insert(args.end(), {"--set", s});
  int status = 0;
  if (waitpid(spawn_self(args, err), &status, 0) < 0) throw std::runtime_error("waitpid failed");
  nlohmann::json j;
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  const std::string why = ok ? "" : last_line(err);
  if (ok) j = nlohmann::json::parse(std::ifstream(stats));
  fs::remove_all(dir);
  if (!ok) throw std::runtime_error("timed raster run failed: " + why);
  return j;
}

}  // namespace rastsim::app
