// SPDX-License-Identifier: Apache-2.0
// The configuration's text forms: the canonical TOML (config_toml) read back gives the
// same config, for every shipped config under random --set overrides, with each
// [section] written once; an unknown key's error suggests the key a typo most likely meant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>

#include "config/config.h"
#include "config/video_timing.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

// Every shipped config, configs/ and its subfolders.
std::vector<std::string> shipped_configs() {
  std::vector<std::string> paths;
  for (const auto& e : fs::recursive_directory_iterator(std::string(RASTSIM_SOURCE_DIR) + "/configs"))
    if (e.is_regular_file() && e.path().extension() == ".toml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// The [section] header lines of a TOML text, in order, repeats kept.
std::vector<std::string> section_headers(const std::string& text) {
  std::vector<std::string> headers;
  std::istringstream is(text);
  for (std::string line; std::getline(is, line);)
    if (!line.empty() && line.front() == '[') headers.push_back(line);
  return headers;
}

// A random value for a key as --set would spell it, meant to be allowed: an integer in
// the range (a power of two half the time, for keys with that rule), a number in the
// range written with 17 digits, either boolean, any enum member, a string from a few
// well-formed ones. Values the config refuses anyway (other rules) are skipped by the caller.
std::string random_value(const ParamDef& d, std::mt19937_64& rng) {
  const bool ranged = d.min <= d.max;
  switch (d.type) {
    case ParamType::Int: {
      const int64_t lo = ranged ? int64_t(d.min) : -1000, hi = ranged ? int64_t(d.max) : 1000;
      int64_t x = std::uniform_int_distribution<int64_t>(lo, hi)(rng);
      if (rng() & 1) {
        int64_t p = 1;
        while (p * 2 <= x) p *= 2;
        x = std::max(p, lo);
      }
      return std::to_string(x);
    }
    case ParamType::Float: {
      const double x = std::uniform_real_distribution<double>(ranged ? d.min : -1e3, ranged ? d.max : 1e3)(rng);
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", x);
      return buf;
    }
    case ParamType::Bool: return (rng() & 1) ? "true" : "false";
    case ParamType::Enum: return d.choices[rng() % d.choices.size()];
    case ParamType::String: {
      const std::vector<std::string> some{"s7.16", "s10.8", "s12.4", "s15.16", "64/16/4", "32/8", "128/32/8/2"};
      return some[rng() % some.size()];
    }
  }
  return "";
}

TEST(ConfigToml, EachSectionOnceInTomlAndDoc) {
  for (const auto& path : shipped_configs()) {
    SCOPED_TRACE(path);
    Config cfg;
    cfg.load_file(path);
    const auto headers = section_headers(config_toml(cfg));
    EXPECT_EQ(std::set<std::string>(headers.begin(), headers.end()).size(), headers.size());
    EXPECT_GE(headers.size(), 5u);
  }
  const auto seen = section_headers(config_doc());
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), seen.size());
}

TEST(ConfigToml, ShippedConfigsRoundTripUnderRandomOverrides) {
  const uint64_t seed = 20261126;
  std::mt19937_64 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  const auto& schema = config_schema();
  size_t checked = 0, overrides = 0;
  for (const auto& path : shipped_configs()) {
    for (int trial = 0; trial < 60; ++trial) {
      Config cfg;
      cfg.load_file(path);
      std::vector<std::string> sets;
      const int n = std::uniform_int_distribution<int>(1, 8)(rng);
      for (int k = 0; k < n; ++k) {
        const ParamDef& d = schema[rng() % schema.size()];
        const std::string set = d.key + "=" + random_value(d, rng);
        try {
          Config next = cfg;
          next.apply_override(set);
          next.validate();
          cfg = next;
          sets.push_back(set);
        } catch (const ConfigError&) {  // another rule refuses it: not an override of this trial
        }
      }
      std::string trace = path;
      for (const auto& s : sets) trace += " --set " + s;
      SCOPED_TRACE(trace);
      const std::string text = config_toml(cfg);
      Config back;
      ASSERT_NO_THROW(back.load_toml(text, "round_trip.toml")) << text;
      ASSERT_NO_THROW(back.validate());
      for (const auto& d : schema)
        EXPECT_TRUE(back.get(d.key) == cfg.get(d.key))
            << d.key << " = " << to_string(cfg.get(d.key)) << " read back as " << to_string(back.get(d.key));
      EXPECT_EQ(config_toml(back), text);
      EXPECT_EQ(config_hash(back), config_hash(cfg));
      ++checked, overrides += sets.size();
    }
  }
  EXPECT_GE(checked, 6u * 60u);
  EXPECT_GE(overrides, checked * 2);  // most random values are allowed
}

// `config --toml` writes every key, the explicit timing keys too: its text must resolve to
// the same video timing (a stats JSON's config_toml reran without the scan-out before, which
// changes simulate's cycles with memory.model = dram), while an explicit key set to
// anything but its default beside a preset is still refused.
TEST(ConfigToml, TextKeepsTheVideoTimingAndAPresetRefusesExplicitKeys) {
  for (const auto& path : shipped_configs()) {
    SCOPED_TRACE(path);
    Config cfg;
    cfg.load_file(path);
    Config back;
    back.load_toml(config_toml(cfg), "round_trip.toml");
    EXPECT_EQ(video_timing_from_config(back), video_timing_from_config(cfg));
  }
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml");  // timing panel, 128 px
  Config same = cfg, other = cfg;
  same.apply_override("display.h_active_px=128");  // the default
  other.apply_override("display.h_active_px=640");
  EXPECT_NO_THROW(video_timing_from_config(same));
  EXPECT_THROW(video_timing_from_config(other), ConfigError);
}

TEST(ConfigToml, StringsWithQuotesAndBackslashesReadBack) {
  // A String key holds any text as far as TOML is concerned: the writer must escape it.
  // raster.coord_format's rule refuses these, so the check goes through the writer alone.
  for (const std::string& s : {std::string("a\"b"), std::string("c:\\dir\\x"), std::string("tab\there")}) {
    const std::string toml = "[x]\nv = " + to_string(ParamValue(s)) + "\n";
    Config cfg;
    try {
      cfg.load_toml(toml, "escape.toml");
      FAIL() << "[x] is no section: expected an unknown-key error";
    } catch (const ConfigError& e) {
      // The parser got past the value: the error is about the key, not the string.
      EXPECT_NE(std::string(e.what()).find("unknown key 'x.v'"), std::string::npos) << e.what();
    }
  }
}

// The error of an unknown key in a file and in --set.
std::string unknown_key_error(const std::string& key) {
  Config cfg;
  try {
    cfg.apply_override(key + "=1");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ConfigKeys, TyposSuggestTheClosestKey) {
  const std::vector<std::pair<std::string, std::string>> typos{
      {"raster.tile_sise", "raster.tile_size"},     // one letter wrong
      {"raster.tiel_size", "raster.tile_size"},     // two letters swapped
      {"raster.tilesize", "raster.tile_size"},      // one left out
      {"raster.tile_sizee", "raster.tile_size"},    // one too many
      {"rastr.tile_size", "raster.tile_size"},      // in the section's name
      {"raster.width", "display.width"},            // in another section
      {"raster.widht", "display.width"},            // in another section, with a typo
      {"raster.depth_fnuc", "raster.depth_func"},
      {"display.heigth", "display.height"},
  };
  for (const auto& [typo, meant] : typos) {
    SCOPED_TRACE(typo);
    const std::string e = unknown_key_error(typo);
    EXPECT_NE(e.find("unknown key '" + typo + "' (did you mean '" + meant + "'?)"), std::string::npos) << e;
  }
  Config cfg;
  try {
    cfg.load_toml("[raster]\ntile_sise = 8\n", "typo.toml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "typo.toml:2: unknown key 'raster.tile_sise' (did you mean 'raster.tile_size'?)");
  }
}

TEST(ConfigKeys, NoSuggestionWithoutACloseKey) {
  for (const char* key : {"raster.nope", "raster.xyzzy_frobnicate", "foo.qux", "raster.tile_sz_max"}) {
    SCOPED_TRACE(key);
    const std::string e = unknown_key_error(key);
    EXPECT_EQ(e.find("did you mean"), std::string::npos) << e;
    EXPECT_NE(e.find("`rastsim config --doc` lists every key"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace rastsim
