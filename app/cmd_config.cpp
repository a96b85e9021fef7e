// SPDX-License-Identifier: Apache-2.0
// `rastsim config`: print the schema (--doc), the stage and FIFO table (--stages) or the
// resolved configuration.
#include <iostream>

#include "common.h"
#include "timing/stage_table.h"

namespace rastsim::app {

namespace {

// timing/stage_table.h as JSON, in pipeline order, with this config's fill cycles and
// link entries: what scripts read instead of a list of their own.
nlohmann::json stage_table_json(const TimingParams& t) {
  nlohmann::json stages = nlohmann::json::array(), fifos = nlohmann::json::array();
  for (const StageInfo& s : kStages)
    stages.push_back({{"index", stage_index(s.id)},
                      {"name", s.name},
                      {"path", s.path == StagePath::Triangle ? "triangle" : "2d"},
                      {"fed_by", stage_name(s.fed_by)},
                      {"fill_cycles", t.stage_fill_cycles(s.id)},
                      {"tile_heat", s.tile_heat}});
  for (const FifoInfo& f : kFifos)
    fifos.push_back({{"name", f.name},
                     {"kind", f.kind == LinkKind::Fifo ? "fifo" : "port_handshake"},
                     {"writer", stage_name(f.writer)},
                     {"reader", stage_name(f.reader)},
                     {"entries", t.fifo_entries(f.id)}});
  return {{"stages", stages}, {"fifos", fifos}};
}

}  // namespace

void register_config(CLI::App& app) {
  auto* cmd = app.add_subcommand("config", "Print the configuration schema or the resolved configuration");
  static ConfigOptions opts;
  static bool doc = false;
  static bool as_toml = false;
  static bool stages = false;
  static bool quiet = false;
  add_config_options(cmd, opts);
  cmd->add_flag("--doc", doc, "Print every key: default, unit, allowed values, description");
  cmd->add_flag("--toml", as_toml, "Print the resolved configuration as TOML (default: key = value  # origin)");
  cmd->add_flag("--stages", stages,
                "Print the pipeline's stages and FIFOs (model/timing/stage_table.h) as JSON, with this config's "
                "fill cycles and FIFO entries");
  add_quiet_flag(cmd, quiet, "anything: only check the configuration, exit status 0 when it is valid");
  cmd->callback([] {
    if (quiet) {
      (void)resolve_arch(opts);  // every check a run makes of it
      return;
    }
    if (doc) {
      std::cout << config_doc();
      return;
    }
    if (stages) {
      std::cout << stage_table_json(resolve_arch(opts).timing).dump(2) << "\n";
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
