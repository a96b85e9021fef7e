// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the config reader (model/config/config.cpp: TOML through toml++,
// schema validation, --set overrides) and the typed parameters built from it.
//
// The input is a TOML file, optionally followed by a line `%%` and then one --set
// assignment per line (section.key=value). The file is written to a scratch path and
// loaded with Config::load_file, the assignments applied with apply_override, then
// validate() and every *_from_config builder the commands call run on the result.
// Bad input may end only in ConfigError. An accepted config must hold, for every schema
// key, a value of the key's type inside its range and choices, which to_string writes
// so that it reads back as the same value.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "config/timing_params.h"
#include "config/video_timing.h"
#include "display/dac.h"
#include "fuzz_common.h"
#include "harness.h"
#include "scene/scene_io.h"

namespace rastsim::fuzz {
namespace {

void check_against_schema(const Config& cfg) {
  Config back;  // each key read back from its to_string (one Config: building one is ~80 keys)
  for (const ParamDef& d : config_schema()) {
    const ParamValue& v = cfg.get(d.key);
    const std::string at = d.key + " = " + to_string(v) + ": ";
    const bool ranged = d.min <= d.max;
    switch (d.type) {
      case ParamType::Int: {
        check(std::holds_alternative<int64_t>(v), at + "not an integer");
        const int64_t x = std::get<int64_t>(v);
        check(!ranged || (double(x) >= d.min && double(x) <= d.max), at + "outside the schema's range");
        break;
      }
      case ParamType::Float: {
        check(std::holds_alternative<double>(v), at + "not a number");
        const double x = std::get<double>(v);
        check(std::isfinite(x) && (!ranged || (x >= d.min && x <= d.max)), at + "outside the schema's range");
        break;
      }
      case ParamType::Bool: check(std::holds_alternative<bool>(v), at + "not a boolean"); break;
      case ParamType::String: check(std::holds_alternative<std::string>(v), at + "not a string"); break;
      case ParamType::Enum: {
        check(std::holds_alternative<std::string>(v), at + "not a string");
        bool found = false;
        for (const auto& c : d.choices) found |= c == std::get<std::string>(v);
        check(found, at + "not one of the choices");
        break;
      }
    }
    if (d.valid) check(d.valid(v), at + "breaks the key's rule (" + d.rule + ")");
    // to_string is how a value leaves the config (`rastsim config [--toml]`, the sweep's
    // config hash, error messages): read back as a --set value it must give the value.
    try {
      back.set_from_string(d.key, to_string(v), "round trip");
    } catch (const ConfigError& e) {
      finding(at + "to_string does not read back: " + e.what());
    }
    check(back.get(d.key) == v, at + "to_string reads back as " + to_string(back.get(d.key)));
  }
}

}  // namespace

void config_one(std::string_view input) {
  const std::string_view in = input;
  const size_t sep = in.find("\n%%\n");
  const std::string path = scratch_file("fuzz.toml", in.substr(0, sep));
  expect_only<ConfigError>("ConfigError", [&] {
    Config cfg;
    cfg.load_file(path);
    check_against_schema(cfg);
    if (sep != std::string_view::npos) {
      std::string_view sets = in.substr(sep + 4);
      while (!sets.empty()) {
        const size_t e = std::min(sets.find('\n'), sets.size());
        if (e > 0) cfg.apply_override(std::string(sets.substr(0, e)));
        sets.remove_prefix(std::min(e + 1, sets.size()));
      }
      check_against_schema(cfg);
    }
    cfg.validate();
    // What every command builds from a validated config.
    (void)raster_state_from_config(cfg);
    (void)TimingParams::from_config(cfg);
    (void)video_timing_from_config(cfg);
    (void)Dac(dac_config_from_config(cfg));
    (void)obj_placement_from_config(cfg);
  });
}

}  // namespace rastsim::fuzz
