// SPDX-License-Identifier: Apache-2.0
#include "config/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "ref/fixed_point.h"
#include "util/hash.h"

namespace rastsim {

namespace {

// A TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_quoted(const std::string& s) {
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      q += '\\', q += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      q += buf;
    } else {
      q += c;
    }
  }
  return q + "\"";
}

}  // namespace

std::string to_string(const ParamValue& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using X = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<X, std::string>) return toml_quoted(x);
        else if constexpr (std::is_same_v<X, bool>) return x ? "true" : "false";
        else if constexpr (std::is_same_v<X, double>) {
          // The shortest text that reads back as the same double ("0.9", "30", "1e-05"):
          // `rastsim config --toml` output and the sweep's config hash must tell apart
          // values that differ past the 6 digits an ostream writes.
          char buf[32];
          return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
        } else return std::to_string(x);
      },
      v);
}

Config::Config() {
  for (const auto& d : config_schema()) {
    values_[d.key] = d.default_value;
    origins_[d.key] = "default";
  }
}

void Config::set_checked(const ParamDef& d, ParamValue v, const std::string& origin) {
  auto bad = [&]() {
    throw ConfigError(origin + ": " + d.key + " = " + to_string(v) + " is not allowed; expected " +
                      d.allowed());
  };
  switch (d.type) {
    case ParamType::Int: {
      const int64_t x = std::get<int64_t>(v);
      if (d.min <= d.max && (double(x) < d.min || double(x) > d.max)) bad();
      break;
    }
    case ParamType::Float: {
      const double x = std::get<double>(v);
      if (!std::isfinite(x) || (d.min <= d.max && (x < d.min || x > d.max))) bad();
      if (x == 0) v = 0.0;  // -0 is 0: TOML reads "-0" as the integer 0, and one config has one text
      break;
    }
    case ParamType::Enum: {
      const auto& x = std::get<std::string>(v);
      bool found = false;
      for (const auto& c : d.choices) found |= (c == x);
      if (!found) bad();
      break;
    }
    default: break;
  }
  if (d.valid && !d.valid(v)) bad();
  values_[d.key] = std::move(v);
  origins_[d.key] = origin;
}

namespace {

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::Int: return "an integer";
    case ParamType::Float: return "a number";
    case ParamType::Bool: return "a boolean";
    case ParamType::String: return "a string";
    case ParamType::Enum: return "a string";
  }
  return "?";
}

std::string short_name(const std::string& key) {
  const auto dot = key.find('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// Optimal string alignment distance: an insertion, a deletion, a substitution or a swap of
// two neighbouring characters (the usual typos) costs 1 each.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The key a mistyped `key` most likely meant, or null: the closest schema key within 2
// edits and a third of the typed length (at least 1), comparing the whole key (a typo
// anywhere, the section's name too) and then the name alone (a key of another section,
// with or without a typo). Ties go to the whole key, then to declaration order.
const ParamDef* closest_key(const std::string& key) {
  const ParamDef* best = nullptr;
  size_t best_distance = SIZE_MAX;
  const auto consider = [&](const ParamDef& d, const std::string& typed, const std::string& known) {
    const size_t limit = std::min<size_t>(2, std::max<size_t>(1, typed.size() / 3));
    const size_t n = edit_distance(typed, known);
    if (n <= limit && n < best_distance) best = &d, best_distance = n;
  };
  for (const auto& d : config_schema()) consider(d, key, d.key);
  for (const auto& d : config_schema()) consider(d, short_name(key), short_name(d.key));
  return best;
}

std::string unknown_key_message(const std::string& key) {
  const std::string msg = "unknown key '" + key + "'";
  if (const ParamDef* d = closest_key(key)) return msg + " (did you mean '" + d->key + "'?)";
  return msg + " (`rastsim config --doc` lists every key)";
}

}  // namespace

void Config::set_from_string(const std::string& key, const std::string& text, const std::string& origin) {
  const ParamDef* d = find_param(key);
  if (!d) throw ConfigError(origin + ": " + unknown_key_message(key));
  auto bad_type = [&]() {
    throw ConfigError(origin + ": " + key + " = '" + text + "' is not " + type_name(d->type) +
                      "; expected " + d->allowed());
  };
  switch (d->type) {
    case ParamType::Int: {
      int64_t x = 0;
      auto r = std::from_chars(text.data(), text.data() + text.size(), x);
      if (r.ec != std::errc() || r.ptr != text.data() + text.size()) bad_type();
      set_checked(*d, x, origin);
      break;
    }
    case ParamType::Float: {
      double x = 0;
      auto r = std::from_chars(text.data(), text.data() + text.size(), x);
      if (r.ec != std::errc() || r.ptr != text.data() + text.size()) bad_type();
      set_checked(*d, x, origin);
      break;
    }
    case ParamType::Bool:
      if (text == "true" || text == "1") set_checked(*d, true, origin);
      else if (text == "false" || text == "0") set_checked(*d, false, origin);
      else bad_type();
      break;
    case ParamType::String:
    case ParamType::Enum: {
      std::string v = text;
      if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
      set_checked(*d, v, origin);
      break;
    }
  }
}

void Config::apply_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set " + assignment + ": expected section.key=value");
  set_from_string(assignment.substr(0, eq), assignment.substr(eq + 1), "--set " + assignment);
}

void Config::load_file(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw ConfigError(path + ": cannot open");
  std::ostringstream text;
  text << is.rdbuf();
  load_toml(text.str(), path);
}

void Config::load_toml(std::string_view text, const std::string& path) {
  toml::table tbl;
  try {
    tbl = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    throw ConfigError(path + ":" + std::to_string(src.begin.line) + ": " + std::string(e.description()));
  }
  source_ = path;
  for (auto&& [sec_key, sec_node] : tbl) {
    const std::string sec(sec_key.str());
    const auto line_of = [&](const toml::node& n) {
      return path + ":" + std::to_string(n.source().begin.line);
    };
    const toml::table* sec_tbl = sec_node.as_table();
    if (!sec_tbl) {
      throw ConfigError(line_of(sec_node) + ": top-level key '" + sec +
                        "' is not a [section]; keys live in sections such as [raster]");
    }
    for (auto&& [k, node] : *sec_tbl) {
      const std::string key = sec + "." + std::string(k.str());
      const std::string where = line_of(node);
      const ParamDef* d = find_param(key);
      if (!d) throw ConfigError(where + ": " + unknown_key_message(key));
      auto bad_type = [&]() {
        throw ConfigError(where + ": " + key + " must be " + type_name(d->type) + " (" + d->allowed() + ")");
      };
      switch (d->type) {
        case ParamType::Int:
          if (auto v = node.value_exact<int64_t>()) set_checked(*d, *v, where);
          else bad_type();
          break;
        case ParamType::Float:
          if (auto v = node.value<double>(); v && (node.is_floating_point() || node.is_integer()))
            set_checked(*d, *v, where);
          else bad_type();
          break;
        case ParamType::Bool:
          if (auto v = node.value_exact<bool>()) set_checked(*d, *v, where);
          else bad_type();
          break;
        case ParamType::String:
        case ParamType::Enum:
          if (auto v = node.value_exact<std::string>()) set_checked(*d, *v, where);
          else bad_type();
          break;
      }
    }
  }
}

const ParamValue& Config::get(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw ConfigError("internal: no config key '" + key + "'");
  return it->second;
}
int64_t Config::get_int(const std::string& key) const { return std::get<int64_t>(get(key)); }
double Config::get_float(const std::string& key) const { return std::get<double>(get(key)); }
bool Config::get_bool(const std::string& key) const { return std::get<bool>(get(key)); }
const std::string& Config::get_string(const std::string& key) const {
  return std::get<std::string>(get(key));
}
const std::string& Config::origin(const std::string& key) const { return origins_.at(key); }

std::string config_toml(const Config& cfg) {
  std::string text, section;
  for (const ParamDef* d : schema_by_section()) {
    const std::string sec = d->key.substr(0, d->key.find('.'));
    if (sec != section) text += (section.empty() ? "[" : "\n[") + sec + "]\n";
    section = sec;
    text += short_name(d->key) + " = " + to_string(cfg.get(d->key)) + "\n";
  }
  return text;
}

std::string config_hash(const Config& cfg) { return hex64(fnv1a64(config_toml(cfg))); }

void validate_traversal(const Config& cfg);  // config_schema_traversal.cpp
void validate_aa(const Config& cfg);         // config_schema_aa.cpp

void Config::validate() const {
  validate_traversal(*this);
  validate_aa(*this);
  const FixedFormat fmt = FixedFormat::parse(get_string("raster.coord_format"));
  const int64_t max_extent = max_viewport_extent(fmt);
  for (const char* k : {"display.width", "display.height"}) {
    const int64_t n = get_int(k);
    if (n > max_extent) {
      throw ConfigError(origin(k) + ": " + k + " = " + std::to_string(n) +
                        " does not fit in raster.coord_format " + fmt.name() + " (" +
                        origin("raster.coord_format") + "): the largest viewport is " +
                        std::to_string(max_extent) + " px");
    }
  }
}

}  // namespace rastsim
