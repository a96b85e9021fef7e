// SPDX-License-Identifier: Apache-2.0
// `rastsim config`: print the schema (--doc), the stage and FIFO table (--stages) or the
// resolved configuration, as TOML too, or the one a stats JSON recorded (--from-stats).
#include <fstream>
#include <iostream>

#include "common.h"
#include "timing/stage_table.h"
#include "util/hash.h"
#include "util/version.h"

namespace rastsim::app {

namespace {

// timing/stage_table.h as JSON, in pipeline order, with this config's fill cycles and
// link entries: what scripts read instead of a list of their own.
nlohmann::json stage_table_json(const TimingParams& t) {
  nlohmann::json stages = nlohmann::json::array(), fifos = nlohmann::json::array();
  for (const StageInfo& s : kStages)
    stages.push_back({{"index", stage_index(s.id)},
                      {"name", s.name},
                      {"path", stage_path_name(s.path)},
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

// --from-stats FILE: the resolved config a stats JSON's provenance recorded, read back
// through this build's schema (a key it does not know fails here, naming the file), then
// the --set overrides. The recorded text must match its recorded hash; a build whose
// schema resolves it to another text (keys added since, or other defaults) says so.
Config config_from_stats(const std::string& path, const std::vector<std::string>& sets) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(std::ifstream(path));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": not a JSON file: " + e.what());
  }
  const nlohmann::json* p = j.is_object() && j.contains("provenance") ? &j["provenance"] : nullptr;
  if (!p || !p->is_object() || !p->contains("config_toml") || !(*p)["config_toml"].is_string() ||
      !p->contains("config_hash"))
    throw std::runtime_error(path + ": no provenance.config_toml and config_hash (the stats JSON of a rastsim "
                             "command records them)");
  const std::string text = (*p)["config_toml"];
  if (hex64(fnv1a64(text)) != (*p)["config_hash"])
    throw std::runtime_error(path + ": provenance.config_toml does not match its config_hash (edited?)");
  Config cfg;
  cfg.load_toml(text, path + " provenance.config_toml");
  cfg.validate();
  if (config_toml(cfg) != text)
    std::cerr << "config: " << path << " was written by rastsim " << p->value("rastsim_version", "?")
              << ", whose keys or defaults differ from this rastsim's (" << rastsim_version()
              << "): printing the recorded config as this rastsim resolves it\n";
  for (const auto& s : sets) cfg.apply_override(s);
  cfg.validate();
  return cfg;
}

// The resolved config, `key = value  # origin`, grouped by section.
void print_with_origins(const Config& cfg) {
  for (const ParamDef* d : schema_by_section())
    std::cout << d->key << " = " << to_string(cfg.get(d->key)) << "  # " << cfg.origin(d->key) << "\n";
}

}  // namespace

void register_config(CLI::App& app) {
  auto* cmd = app.add_subcommand("config", "Print the configuration schema or the resolved configuration");
  static ConfigOptions opts;
  static bool doc = false;
  static bool as_toml = false;
  static bool stages = false;
  static std::string from_stats;
  static bool quiet = false;
  add_config_options(cmd, opts);
  cmd->add_flag("--doc", doc, "Print every key: default, unit, allowed values, description");
  cmd->add_flag("--toml", as_toml,
                "Print the resolved configuration as canonical TOML, which --config reads back to the same "
                "config (default: key = value  # origin)");
  cmd->add_option("--from-stats", from_stats,
                  "Print, as --toml, the resolved config recorded in a stats JSON's provenance (then any --set): "
                  "`--config` of it reproduces that run's config")
      ->check(CLI::ExistingFile);
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
    if (!from_stats.empty()) {
      if (!opts.config_path.empty()) throw std::runtime_error("config: --from-stats and --config exclude each other");
      std::cout << config_toml(config_from_stats(from_stats, opts.sets));
      return;
    }
    const Config cfg = load_config(opts);
    if (as_toml) std::cout << config_toml(cfg);
    else print_with_origins(cfg);
  });
}

}  // namespace rastsim::app
