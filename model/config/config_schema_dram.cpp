// SPDX-License-Identifier: Apache-2.0
// Keys of the DRAM model (docs/memory.md): memory.preset picks a shipped parameter set
// (configs/memory/*.toml, compiled in), and each dram.* key overrides one of its values;
// a dram.* key left at 0 ("" or "preset") takes the preset's. The preset files set every
// dram.* key and nothing else, and are read with this same schema, so a bad value in one
// is reported with its file and line.
#include <algorithm>
#include <cmath>

#include "config/config_schema.h"
#include "config/dram_config.h"

namespace rastsim {

namespace {

// One integer dram.* key and the DramParams member it sets (wide or narrow).
struct DramIntKey {
  const char* name;
  const char* unit;
  double max;
  const char* description;
  int64_t DramParams::*wide = nullptr;
  int DramParams::*narrow = nullptr;
};

const std::vector<DramIntKey>& dram_int_keys() {
  using P = DramParams;
  static const std::vector<DramIntKey> keys = {
      {"channels", "", 64, "Independent channels (a power of two)", nullptr, &P::channels},
      {"bank_groups", "", 16, "Bank groups a channel (1: none; a power of two)", nullptr, &P::bank_groups},
      {"banks_per_group", "", 64, "Banks a bank group (a power of two)", nullptr, &P::banks_per_group},
      {"rows", "", 1 << 24, "Rows a bank (a power of two)", &P::rows},
      {"columns", "", 1 << 20, "Column addresses a row, each bus_bits wide (a power of two)", &P::columns},
      {"bus_bits", "bits", 1024, "Data bus width of a channel", nullptr, &P::bus_bits},
      {"burst_length", "", 64, "BL: data transfers a column access", nullptr, &P::burst_length},
      {"transfers_per_clock", "", 16, "Data transfers a pin a DRAM clock (2: DDR)", nullptr,
       &P::transfers_per_clock},
      {"queue_depth", "bursts", 4096, "Scheduler queue of a channel (FR-FCFS over these)", nullptr, &P::queue_depth},
      {"tcl", "clocks", 1000, "CL: read command to first data", &P::tCL},
      {"tcwl", "clocks", 1000, "CWL: write command to first data", &P::tCWL},
      {"trcd", "clocks", 1000, "tRCD: activate to read", &P::tRCD},
      {"trcd_wr", "clocks", 1000, "tRCD for writes (GDDR6 tRCDWR; DDR4/LPDDR4: = tRCD)", &P::tRCD_WR},
      {"trp", "clocks", 1000, "tRP: precharge to activate", &P::tRP},
      {"tras", "clocks", 1000, "tRAS: activate to precharge", &P::tRAS},
      {"trc", "clocks", 1000, "tRC: activate to activate, same bank", &P::tRC},
      {"tccd_s", "clocks", 1000, "tCCD_S: column to column, other bank group", &P::tCCD_S},
      {"tccd_l", "clocks", 1000, "tCCD_L: column to column, same bank group", &P::tCCD_L},
      {"trrd_s", "clocks", 1000, "tRRD_S: activate to activate, other bank group", &P::tRRD_S},
      {"trrd_l", "clocks", 1000, "tRRD_L: activate to activate, same bank group", &P::tRRD_L},
      {"tfaw", "clocks", 10000, "tFAW: window holding at most four activates", &P::tFAW},
      {"t32aw", "clocks", 100000, "t32AW (GDDR): window holding at most 32 activates", &P::t32AW},
      {"twr", "clocks", 1000, "tWR: end of write data to precharge", &P::tWR},
      {"twtr_s", "clocks", 1000, "tWTR_S: end of write data to read, other bank group", &P::tWTR_S},
      {"twtr_l", "clocks", 1000, "tWTR_L: end of write data to read, same bank group", &P::tWTR_L},
      {"trtp", "clocks", 1000, "tRTP: read to precharge", &P::tRTP},
      {"trefi", "clocks", 1e7, "tREFI: all-bank refresh interval", &P::tREFI},
      {"trfc", "clocks", 1e5, "tRFC: refresh to activate", &P::tRFC},
  };
  return keys;
}

bool is_address_map(const ParamValue& v) {
  const std::string& s = std::get<std::string>(v);
  if (s.empty()) return true;
  try {
    parse_address_map(s);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

// The config's value of `key` when set to a non-default value, else the preset's.
const ParamValue& pick(const Config& cfg, const Config& preset, const std::string& key) {
  const ParamValue& v = cfg.get(key);
  const bool unset = v == find_param(key)->default_value;
  return unset ? preset.get(key) : v;
}

// dram.* keys of the controller that no preset sets: the config's value is used as it is.
constexpr const char* kStarvationKey = "dram.starvation_cycles";

// The preset file, read with the schema; it must set every dram.* key (but the
// controller's own above) and no other.
Config load_preset(const std::string& name) {
  const auto& files = dram_preset_files();
  auto it = std::find_if(files.begin(), files.end(), [&](const EmbeddedText& f) { return f.name == name + ".toml"; });
  if (it == files.end()) throw ConfigError("memory.preset: no preset \"" + name + "\"");
  const std::string source = "configs/memory/" + name + ".toml";
  Config preset;
  preset.load_toml(it->text, source);
  for (const auto& [key, value] : preset.values()) {
    const bool dram = key.rfind("dram.", 0) == 0 && key != kStarvationKey, set = preset.origin(key) != "default";
    if (dram && (!set || value == find_param(key)->default_value))
      throw ConfigError(source + ": sets no value for " + key + " (a preset sets every dram.* key)");
    if (!dram && set)
      throw ConfigError(source + ": sets " + key + " (a preset sets only dram.* keys, not " + kStarvationKey + ")");
  }
  return preset;
}

}  // namespace

std::vector<std::string> dram_preset_names() {
  std::vector<std::string> names;
  for (const EmbeddedText& f : dram_preset_files()) {
    std::string n(f.name);
    names.push_back(n.substr(0, n.size() - std::string(".toml").size()));
  }
  return names;
}

void add_dram_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  auto add = [&](ParamDef d) { s.push_back(std::move(d)); };
  add({"memory.preset", T::Enum, std::string("ddr4_2400"), "", 1, 0, dram_preset_names(),
       "DRAM parameter set (configs/memory/<name>.toml: organisation and JEDEC timing, each value's source "
       "cited there); dram.* keys override single values"});
  add({"dram.clock_mhz", T::Float, 0.0, "MHz", 0, 10000, {},
       "DRAM command clock CK; every dram.t* key counts these clocks (0: the preset's)"});
  for (const DramIntKey& k : dram_int_keys())
    add({std::string("dram.") + k.name, T::Int, int64_t{0}, k.unit, 0, k.max, {},
         std::string(k.description) + " (0: the preset's)"});
  add({"dram.page_policy", T::Enum, std::string("preset"), "", 1, 0, {"preset", "open", "closed"},
       "open: a row stays open until a conflict or refresh; closed: every access auto-precharges"});
  add({kStarvationKey, T::Int, int64_t{0}, "cycles", 0, 1e7, {},
       "Starvation cap of the FR-FCFS scheduler: a burst waiting this many core cycles in its channel's queue is "
       "served next (its bank serves no younger row hit first; other banks only commands that issue before it) "
       "(0: off; not a preset value)"});
  add({"dram.address_map", T::String, std::string(""), "", 1, 0, {},
       "Byte address fields above the burst offset, MSB first: ro (row), ch (channel), ba (bank), bg (bank "
       "group), co (column in bursts), e.g. \"ro:ba:co:bg:ch\" (\"\": the preset's)",
       is_address_map, "empty, or each of ro, ch, ba, bg, co once, separated by ':'"});
}

DramParams dram_params_from_config(const Config& cfg) {
  DramParams p;
  p.preset = cfg.get_string("memory.preset");
  const Config preset = load_preset(p.preset);
  for (const DramIntKey& k : dram_int_keys()) {
    const int64_t v = std::get<int64_t>(pick(cfg, preset, std::string("dram.") + k.name));
    if (k.wide) p.*k.wide = v;
    else p.*k.narrow = int(v);
  }
  auto khz = [](double mhz) { return uint64_t(std::llround(mhz * 1000)); };
  p.core_khz = khz(cfg.get_float("clock.core_mhz"));
  p.dram_khz = khz(std::get<double>(pick(cfg, preset, "dram.clock_mhz")));
  p.page_policy = std::get<std::string>(pick(cfg, preset, "dram.page_policy")) == "closed" ? PagePolicy::Closed
                                                                                           : PagePolicy::Open;
  p.starvation_cycles = uint64_t(cfg.get_int(kStarvationKey));
  p.address_map = parse_address_map(std::get<std::string>(pick(cfg, preset, "dram.address_map")));
  if (const std::string why = p.check(); !why.empty())
    throw ConfigError("memory.preset = \"" + p.preset + "\" with the config's dram.* keys: " + why);
  return p;
}

}  // namespace rastsim
