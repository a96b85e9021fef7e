// SPDX-License-Identifier: Apache-2.0
// `rastsim recip-grid`: the newton reciprocal's error against interp.recip = "exact" at
// every seed table width and Newton-Raphson step count (ref/study/recip_grid.h,
// docs/clip-space.md "Reciprocal precision"), as CSV a row a setting.
#include <cstdio>
#include <iostream>

#include "common.h"
#include "config/raster_state_config.h"
#include "ref/study/recip_grid.h"
#include "scene/scene_io.h"
#include "util/atomic_file.h"

namespace rastsim::app {

namespace {

struct RecipGridOptions {
  ConfigOptions config;
  std::string scene_path, output_path = "-";
  bool quiet = false;
};

constexpr const char* kCsvHeader =
    "scene,seed_bits,iterations,fragments,colour_values,colour_wrong,colour_max_lsb,colour_mean_lsb,"
    "texcoord_values,texcoord_wrong,texcoord_max_lsb,texcoord_mean_lsb,exact";

void write_csv(std::ostream& os, const std::string& scene, const RecipGrid& g) {
  os << kCsvHeader << "\n";
  char mean[64];
  for (const RecipGridRow& r : g.rows) {
    os << scene << "," << r.seed_bits << "," << r.iterations << "," << g.fragments;
    for (const AttributeError* e : {&r.colour, &r.texcoord}) {
      std::snprintf(mean, sizeof mean, "%.9g", e->mean());
      os << "," << e->values << "," << e->wrong << "," << e->max << "," << mean;
    }
    os << "," << (r.exact() ? 1 : 0) << "\n";
  }
}

// The summary: for each step count, the fewest seed bits exact on the scene and the
// errors at 8 seed bits (the default table).
void print_summary(std::ostream& out, const std::string& scene, const RecipGrid& g) {
  out << "recip-grid: " << scene << ", " << g.fragments << " fragments, " << g.rows.size()
      << " newton settings against exact\n";
  for (const RecipGridRow& r : g.rows) {
    if (r.seed_bits != 8) continue;
    int fewest = 0;
    for (const RecipGridRow& o : g.rows)
      if (o.iterations == r.iterations && o.exact() && !fewest) fewest = o.seed_bits;
    char line[200];
    std::snprintf(line, sizeof line,
                  "  %d steps: exact from %s; at 8 seed bits colour max %llu mean %.3g, texcoord max %llu mean %.3g LSB\n",
                  r.iterations, fewest ? (std::to_string(fewest) + " seed bits").c_str() : "no width <= 16",
                  static_cast<unsigned long long>(r.colour.max), r.colour.mean(),
                  static_cast<unsigned long long>(r.texcoord.max), r.texcoord.mean());
    out << line;
  }
}

void run_recip_grid_command(const RecipGridOptions& o) {
  check_writable(o.output_path);
  const ArchParams arch = resolve_arch(o.config, o.scene_path);
  const Scene scene = load_scene(o.scene_path, arch.placement);
  const RecipGrid g = recip_grid(scene, arch.raster);
  if (o.output_path == "-") {
    write_csv(std::cout, o.scene_path, g);
  } else {
    AtomicFile f(o.output_path);
    write_csv(f.stream(), o.scene_path, g);
    f.commit();
  }
  print_summary(summary_stream(o.output_path, o.quiet), o.scene_path, g);
}

}  // namespace

void register_recip_grid(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "recip-grid",
      "Render a scene with interp.recip = newton at seed bits 1..16 x iterations 0..4 and measure each "
      "fragment's colour and texture coordinates against interp.recip = exact (docs/clip-space.md)");
  static RecipGridOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("--output", o.output_path,
                  "CSV to write ('-': stdout, the summary then on stderr), a row a setting: scene, seed_bits, "
                  "iterations, fragments, colour_ and texcoord_ values, wrong, max_lsb, mean_lsb, exact (1: every "
                  "value equals exact's)")
      ->capture_default_str();
  add_quiet_flag(cmd, o.quiet, "the summary");
  cmd->callback([] { run_recip_grid_command(o); });
}

}  // namespace rastsim::app
