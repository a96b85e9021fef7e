// SPDX-License-Identifier: Apache-2.0
// `rastsim coverage-error`: each sample count's coverage masks against the exact area
// coverage of every edge pixel (model/aa, docs/exact-coverage.md).
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "aa/coverage_error.h"
#include "common.h"
#include "config/raster_state_config.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"

namespace rastsim::app {

namespace {

struct CoverageErrorOptions {
  ConfigOptions config;
  std::string scene_path, stats_path;
  std::vector<int> samples{1, 2, 4, 8, 16};
  bool quiet = false;
};

void run_coverage_error_command(const CoverageErrorOptions& o) {
  const ArchParams arch = resolve_arch(o.config, o.scene_path);
  for (int s : o.samples) {  // each count through the config's own checks (e.g. scanline)
    ConfigOptions with = o.config;
    with.sets.push_back("raster.samples=" + std::to_string(s));
    try {
      (void)load_config(with);
    } catch (const std::exception& e) {
      throw std::runtime_error("--samples " + std::to_string(s) + " (as " + e.what() + ")");
    }
  }
  const Scene scene = load_scene(o.scene_path, arch.placement);
  const CoverageErrorResult r = measure_coverage_error(scene, arch.raster, o.samples);
  nlohmann::json j;
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, arch.placement.camera);
  j["pixels_clipped"] = r.pixels_clipped;
  j["wall_seconds"] = r.wall_seconds;
  for (const CoverageErrorStats& s : r.per_samples)
    j["samples"][std::to_string(s.samples)] = {{"triangles", s.triangles},
                                               {"edge_pixels", s.edge_pixels},
                                               {"coverage_error_mean", s.mean()},
                                               {"coverage_error_rms", s.rms()},
                                               {"coverage_error_max", s.error_max}};
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  char line[160];
  std::snprintf(line, sizeof line, " (%llu pixels clipped exactly, %.2f s)\n",
                static_cast<unsigned long long>(r.pixels_clipped), r.wall_seconds);
  out << "coverage error of " << o.scene_path << line;
  std::snprintf(line, sizeof line, "%7s %10s %11s %8s %8s %8s\n", "samples", "triangles", "edge_pixels", "mean", "rms",
                "max");
  out << line;
  for (const CoverageErrorStats& s : r.per_samples) {
    std::snprintf(line, sizeof line, "%7d %10llu %11llu %8.4f %8.4f %8.4f\n", s.samples,
                  static_cast<unsigned long long>(s.triangles), static_cast<unsigned long long>(s.edge_pixels),
                  s.mean(), s.rms(), s.error_max);
    out << line;
  }
}

}  // namespace

void register_coverage_error(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "coverage-error",
      "Measure each sample count's coverage masks against the exact area coverage of every edge pixel "
      "(docs/exact-coverage.md)");
  static CoverageErrorOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("--samples", o.samples,
                  "Sample counts to measure, comma-separated, each 1, 2, 4, 8 or 16 (overrides raster.samples)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--stats", o.stats_path,
                  "Write the figures as JSON ('-' for stdout, the table then on stderr): samples.<N>.edge_pixels, "
                  "coverage_error_mean, coverage_error_rms, coverage_error_max, triangles; pixels_clipped, "
                  "wall_seconds");
  add_quiet_flag(cmd, o.quiet, "the table");
  cmd->callback([] { run_coverage_error_command(o); });
}

}  // namespace rastsim::app
