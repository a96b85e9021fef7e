// SPDX-License-Identifier: Apache-2.0
// Architecture configuration: one schema declared in C++ (config_schema.cpp), values
// from TOML files and --set overrides, validated against the schema.
//
// Configuration flows one way: file -> Config -> typed parameter structs (RasterState,
// the timed model's stage parameters, the RTL parameter package). Nothing downstream
// keeps a default of its own: every default lives in the schema.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rastsim {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using ParamValue = std::variant<int64_t, double, bool, std::string>;

enum class ParamType { Int, Float, Bool, String, Enum };

struct ParamDef {
  std::string key;           // "section.name"; units go in the name where they matter
  ParamType type;
  ParamValue default_value;
  std::string unit;          // "px", "cycles", "MHz", "" ...
  double min = 0, max = 0;   // inclusive range for Int/Float (ignored when min > max)
  std::vector<std::string> choices;  // for Enum
  std::string description;   // one line
  // Extra rule beyond type/range/choices: a predicate and the phrase that states it
  // (e.g. "a power of two"), shown in errors and in --doc.
  bool (*valid)(const ParamValue&) = nullptr;
  std::string rule;
  std::string allowed() const;  // human-readable allowed set, for errors and --doc
};

// The one schema, in declaration order.
const std::vector<ParamDef>& config_schema();
const ParamDef* find_param(const std::string& key);

// The schema grouped by section: the sections in the order of their first key, the keys
// of a section in declaration order (a group's file may add keys to an earlier section,
// as config_schema_scanout.cpp does to [display]). The order of `rastsim config`, its
// --doc and the canonical TOML, where a [section] may appear only once.
const std::vector<const ParamDef*>& schema_by_section();

// Human-readable schema (for `rastsim config --doc`).
std::string config_doc();

class Config {
 public:
  Config();  // all defaults

  // Loads a TOML file over the current values. Throws ConfigError "file:line: ...".
  void load_file(const std::string& path);
  // Loads TOML text over the current values; `source` names it in errors ("source:line").
  void load_toml(std::string_view text, const std::string& source);
  // Applies "section.key=value" (value parsed by the key's type). Throws ConfigError.
  void apply_override(const std::string& assignment);
  // Sets one key from a string value (as --set would); `origin` goes in errors.
  void set_from_string(const std::string& key, const std::string& value, const std::string& origin);

  int64_t get_int(const std::string& key) const;
  double get_float(const std::string& key) const;
  bool get_bool(const std::string& key) const;
  const std::string& get_string(const std::string& key) const;  // String and Enum
  const ParamValue& get(const std::string& key) const;
  // Where a value came from: "default", "file:line" or "--set".
  const std::string& origin(const std::string& key) const;

  const std::map<std::string, ParamValue>& values() const { return values_; }
  std::string source_name() const { return source_; }

  // Checks across keys that the schema cannot express alone (e.g. the display must fit
  // in the coordinate format). Throws ConfigError naming the keys.
  void validate() const;

 private:
  void set_checked(const ParamDef& def, ParamValue v, const std::string& origin);
  std::map<std::string, ParamValue> values_;
  std::map<std::string, std::string> origins_;
  std::string source_ = "defaults";
};

// A value as TOML writes it: strings quoted and escaped, floats in the shortest form that
// reads back as the same double.
std::string to_string(const ParamValue& v);

// The canonical TOML text of a resolved config: every key of the schema, each [section]
// once (schema_by_section()), `name = value` as to_string() writes it. Config::load_toml
// of it gives the same value for every key. `rastsim config --toml` prints it; the stats'
// provenance records it.
std::string config_toml(const Config& cfg);

// The fingerprint of a resolved config: FNV-1a 64 (util/hash.h) of config_toml(), 16
// lower-case hex digits. Equal configs have equal hashes (the sweep CSV's row key).
std::string config_hash(const Config& cfg);

}  // namespace rastsim
