// SPDX-License-Identifier: Apache-2.0
// `rastsim config`: print the schema (--doc) or the resolved configuration.
#include <iostream>

#include "common.h"

namespace rastsim::app {

void register_config(CLI::App& app) {
  auto* cmd = app.add_subcommand("config", "Print the configuration schema or the resolved configuration");
  static ConfigOptions opts;
  static bool doc = false;
  static bool as_toml = false;
  add_config_options(cmd, opts);
  cmd->add_flag("--doc", doc, "Print every key: default, unit, allowed values, description");
  cmd->add_flag("--toml", as_toml, "Print the resolved configuration as TOML (default: key = value  # origin)");
  cmd->callback([] {
    if (doc) {
      std::cout << config_doc();
      return;
    }
    const Config cfg = load_config(opts);
    std::string section;
    for (const auto& d : config_schema()) {
      const std::string sec = d.key.substr(0, d.key.find('.'));
      const std::string name = d.key.substr(d.key.find('.') + 1);
      if (as_toml) {
        if (sec != section) std::cout << (section.empty() ? "" : "\n") << "[" << sec << "]\n";
        std::cout << name << " = " << to_string(cfg.get(d.key)) << "\n";
      } else {
        std::cout << d.key << " = " << to_string(cfg.get(d.key)) << "  # " << cfg.origin(d.key) << "\n";
      }
      section = sec;
    }
  });
}

}  // namespace rastsim::app
