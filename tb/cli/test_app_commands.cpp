// SPDX-License-Identifier: Apache-2.0
// The `rastsim` commands called as plain functions (run_*_command with an options
// struct), as the command-line callbacks call them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common.h"

namespace rastsim::app {
namespace {

const std::string kSrc = RASTSIM_SOURCE_DIR;

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream is(p);
  return nlohmann::json::parse(is);
}

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("rastsim_app_tests_" + std::to_string(::getpid()) + "_" + name);
}

// The CRC of traces/state.trace with configs/default.toml, as `rastsim render` printed it
// before the commands became plain functions.
TEST(AppCommands, RenderWritesStatsWithHexCrc) {
  RenderOptions o;
  o.config.config_path = kSrc + "/configs/default.toml";
  o.scene_path = kSrc + "/traces/state.trace";
  o.stats_path = temp_file("render.json").string();
  o.quiet = true;
  run_render_command(o);
  const nlohmann::json j = read_json(o.stats_path);
  std::filesystem::remove(o.stats_path);
  EXPECT_EQ(j.at("framebuffer_crc32"), "db225d0d");
  EXPECT_EQ(j.at("fragments"), 9318);
  EXPECT_EQ(j.at("scene"), o.scene_path);
}

TEST(AppCommands, RenderRejectsAnUnknownSetKey) {
  RenderOptions o;
  o.config.config_path = kSrc + "/configs/default.toml";
  o.config.sets = {"raster.no_such_key=1"};
  o.scene_path = kSrc + "/traces/state.trace";
  o.quiet = true;
  try {
    run_render_command(o);
    FAIL() << "an unknown --set key was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("raster.no_such_key"), std::string::npos) << e.what();
  }
}

TEST(AppCommands, SweepRejectsABadAxisBeforeRunning) {
  SweepOptions o;
  o.base.config_path = kSrc + "/configs/default.toml";
  o.scenes = {kSrc + "/traces/state.trace"};
  o.set_args = {"raster.tile_size=16,17"};  // 17 is not a power of two
  o.out_path = temp_file("sweep.csv").string();
  EXPECT_THROW(run_sweep_command(o), std::exception);
  EXPECT_FALSE(std::filesystem::exists(o.out_path));
}

}  // namespace
}  // namespace rastsim::app
