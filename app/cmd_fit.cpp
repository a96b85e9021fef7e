// SPDX-License-Identifier: Apache-2.0
// `rastsim fit`: the narrowest raster.coord_format a scene needs (ref/study/coord_fit.h) and
// the datapath widths it implies (datapath_widths, as export-rtl); with --precision,
// the coordinate-precision table of docs/stability.md for F = 0..16.
#include <iostream>

#include "common.h"
#include "config/raster_state_config.h"
#include "ref/study/coord_fit.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"

namespace rastsim::app {

namespace {

struct FitOptions {
  ConfigOptions config;
  std::string scene_path, stats_path;
  bool format_only = false, precision = false, quiet = false;
};

nlohmann::json widths_json(const DatapathWidths& w) {
  return {{"coord", w.coord}, {"edge_coef", w.coef}, {"edge", w.edge}, {"area", w.area},
          {"color_num", w.color_num}, {"depth_num", w.depth_num}};
}

// The fit as the report prints it (not with --format-only).
void print_fit(std::ostream& out, const FitOptions& o, const Config& cfg, const CoordFit& fit) {
  const DatapathWidths& w = fit.widths;
  out << "fit: " << o.scene_path << " (" << cfg.source_name() << ")\n"
      << "  integer bits " << fit.widest.int_bits << ": viewport needs " << fit.int_bits_viewport
      << ", vertices need " << fit.int_bits_vertices << "\n"
      << "  reference " << fit.widest.name() << " (I + F = " << kMaxFormatBits << "): crc32 "
      << crc32_hex(fit.reference.color_crc32) << ", " << fit.reference.fragments << " fragments (crc32 "
      << crc32_hex(fit.reference.fragments_crc32) << ")\n"
      << "  raster.coord_format = \"" << fit.format.name() << "\": identical framebuffer and fragment stream";
  if (fit.format.frac_bits > 1) out << "; " << FixedFormat{fit.format.int_bits, fit.format.frac_bits - 1}.name() << " differs";
  out << "\n";
  if (fit.format.frac_bits == 1)
    out << (fit.exact_at_zero_frac ? "  exact at 0 fraction bits: integer vertices render identically (F = 1 is the "
                                     "smallest format, pixel centres sit at +0.5)\n"
                                   : "  not exact at 0 fraction bits: integer vertices render differently\n");
  out << "  weaker identities, fewest F with the same coverage: "
      << FixedFormat{fit.format.int_bits, fit.coverage_frac_bits}.name() << ", with the same colour buffer: "
      << FixedFormat{fit.format.int_bits, fit.color_frac_bits}.name() << " (depth and colour see every vertex LSB)\n";
  out << "  widths (bits): vertex " << w.coord << ", edge a/b " << w.coef << ", edge c/E " << w.edge << ", area "
      << w.area << " unsigned, colour numerator " << w.color_num << " unsigned, depth numerator " << w.depth_num
      << " unsigned (docs/fixed-point.md)\n";
}

// --precision: the table on `out` (a Markdown table, docs/stability.md) and as JSON.
nlohmann::json precision_table(const Scene& scene, const RasterState& arch, const CoordFit& fit, std::ostream& out) {
  const auto rows = measure_precision(scene, arch, fit.widest.int_bits, 16);
  nlohmann::json pj = nlohmann::json::array();
  out << "\n| F | format | pixels != F=16 | cracks | edge width |\n|---|---|---|---|---|\n";
  for (const PrecisionRow& r : rows) {
    nlohmann::json rj = {{"frac_bits", r.frac_bits}, {"format", r.format.name()}, {"edge_width", r.edge_width}};
    if (r.ok) {
      rj["pixels_different"] = r.pixels_different;
      if (r.cracks) rj["cracks"] = *r.cracks;
    } else {
      rj["error"] = r.error;
    }
    pj.push_back(rj);
    out << "| " << r.frac_bits << " | " << (r.frac_bits == 0 ? "integer vertices in " : "") << r.format.name()
        << " | " << (r.ok ? std::to_string(r.pixels_different) : "render fails") << " | "
        << (r.cracks ? std::to_string(*r.cracks) : "n/a") << " | " << r.edge_width << " |\n";
  }
  return pj;
}

// The perspective datapath's widths (fit_recip): printed on `out`, returned as JSON.
nlohmann::json recip_fit(const Scene& scene, const RasterState& arch, std::ostream& out) {
  const RecipFit f = fit_recip(scene, arch);
  nlohmann::json j = {{"triangles", f.triangles}, {"perspective_triangles", f.perspective_triangles},
                      {"max_abs_texcoord", f.max_abs_texcoord}, {"texcoord_int_bits", f.texcoord_int_bits}};
  out << "  texture coordinates: largest |s|, |t| " << f.max_abs_texcoord << " repeats: interp.texcoord_format needs "
      << f.texcoord_int_bits << " integer bits (s" << f.texcoord_int_bits << ".F)\n";
  if (f.perspective_triangles == 0) {
    out << "  reciprocal: no triangle of " << f.triangles << " has unequal 1/w: interp.recip is never used\n";
    return j;
  }
  nlohmann::json seeds = nlohmann::json::object();
  out << "  reciprocal: " << f.perspective_triangles << " of " << f.triangles
      << " triangles take one; interp.recip = newton renders as exact with";
  for (int it = 0; it <= kRecipFitIterations; ++it) {
    const int b = f.seed_bits[size_t(it)];
    seeds[std::to_string(it)] = b;
    out << (it ? ", " : " ") << it << " steps: " << (b ? std::to_string(b) + " seed bits" : "no seed width <= 16");
  }
  out << "\n";
  j["fewest_seed_bits_by_iterations"] = seeds;
  return j;
}

void run_fit_command(const FitOptions& o) {
  check_one_stdout({{"--stats", o.stats_path}, {"--format-only", o.format_only ? "-" : ""}});
  const ArchParams params = resolve_arch(o.config, o.scene_path);
  const RasterState& arch = params.raster;
  const Scene scene = load_scene(o.scene_path, params.placement);
  const CoordFit fit = fit_coord_format(scene, arch);
  nlohmann::json j;
  j["config"] = params.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, params.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, params.placement.camera);
  j["coord_format"] = fit.format.name();
  j["reference_format"] = fit.widest.name();
  j["int_bits_viewport"] = fit.int_bits_viewport;
  j["int_bits_vertices"] = fit.int_bits_vertices;
  j["exact_at_zero_frac"] = fit.exact_at_zero_frac;
  j["framebuffer_crc32"] = crc32_hex(fit.reference.color_crc32);
  j["fragments_crc32"] = crc32_hex(fit.reference.fragments_crc32);
  j["fragments"] = fit.reference.fragments;
  j["widths"] = widths_json(fit.widths);
  j["coverage_format"] = FixedFormat{fit.format.int_bits, fit.coverage_frac_bits}.name();
  j["color_format"] = FixedFormat{fit.format.int_bits, fit.color_frac_bits}.name();
  j["renders"] = fit.trials.size() + 1;
  // --format-only's one line is the command's product (for $(...)); the report is text.
  std::ostream& out = summary_stream(o.stats_path, o.quiet || o.format_only);
  if (o.format_only) std::cout << fit.format.name() << "\n";
  print_fit(out, o, params.config, fit);
  if (!o.format_only) j["perspective"] = recip_fit(scene, arch, out);
  if (o.precision) j["precision"] = precision_table(scene, arch, fit, out);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
}

}  // namespace

void register_fit(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "fit",
      "The narrowest raster.coord_format whose render of a scene is identical (framebuffer CRC and fragment "
      "stream) to the widest format with the same integer bits (I + F = 31), and the widths it implies");
  static FitOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_flag("--format-only", o.format_only,
                "Print only the format, e.g. --set raster.coord_format=$(rastsim fit ... --format-only)");
  cmd->add_option("--stats", o.stats_path, "Write the fit (and the precision table) as JSON to this file ('-' for stdout)");
  cmd->add_flag("--precision", o.precision,
                "Also measure F = 0..16 at the fitted integer bits: pixels different from F = 16, cracks of a closed "
                "mesh, edge width (docs/stability.md)");
  add_quiet_flag(cmd, o.quiet, "the report; --format-only still prints the format");
  cmd->callback([] { run_fit_command(o); });
}

}  // namespace rastsim::app
