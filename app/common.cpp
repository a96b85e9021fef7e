// SPDX-License-Identifier: Apache-2.0
#include "common.h"

#include <fstream>
#include <iostream>

namespace rastsim::app {

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

ObjPlacement obj_placement(const Config& cfg) {
  ObjPlacement p;
  p.viewport_width = static_cast<int>(cfg.get_int("display.width"));
  p.viewport_height = static_cast<int>(cfg.get_int("display.height"));
  p.yaw_deg = cfg.get_float("scene.obj_yaw_deg");
  p.pitch_deg = cfg.get_float("scene.obj_pitch_deg");
  p.fill = cfg.get_float("scene.obj_fill");
  return p;
}

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

}  // namespace rastsim::app
