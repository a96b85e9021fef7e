// SPDX-License-Identifier: Apache-2.0
// `rastsim render`: the reference model on one scene; image, stats, fragment trace.
#include <fstream>
#include <iostream>

#include "common.h"
#include "ref/pipeline.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"
#include "display/image_io.h"
#include "config/raster_state_config.h"

namespace rastsim::app {

void register_render(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a scene with the bit-exact reference model");
  static ConfigOptions opts;
  static std::string scene_path, out_path, stats_path, frag_path;
  static bool quiet = false;
  add_config_options(cmd, opts);
  cmd->add_option("--scene,-s", scene_path, "Scene: a trace (.trace, docs/trace-format.md) or a Wavefront OBJ (.obj)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", out_path, "Image to write: .png or .ppm (colour buffer, RGB)");
  cmd->add_option("--stats", stats_path, "Write the stats as JSON to this file ('-' for stdout)");
  cmd->add_option("--fragments", frag_path,
                  "Write every fragment leaving interpolation, one 'x y z r g b' line each, in pipeline order");
  cmd->add_flag("--quiet,-q", quiet, "Do not print the summary line");
  cmd->callback([] {
    const Config cfg = load_config(opts);
    const RasterState arch = raster_state_from_config(cfg);
    const Scene scene = load_scene(scene_path, obj_placement(cfg));
    RenderStats stats;
    std::ofstream frag_os;
    FragmentSink sink;
    if (!frag_path.empty()) {
      frag_os.open(frag_path);
      if (!frag_os) throw std::runtime_error(frag_path + ": cannot open for writing");
      sink = [&](const Fragment& f) { frag_os << fragment_trace_line(f) << '\n'; };
    }
    const Framebuffer fb = render_scene(scene, arch, stats, sink);
    if (!out_path.empty()) write_image(fb, out_path);
    nlohmann::json j = to_json(stats);
    j["config"] = cfg.source_name();
    j["scene"] = scene_path;
    if (!stats_path.empty()) write_json(stats_path, j);
    if (!quiet) {
      std::cout << "render: " << stats.triangles_in << " triangles (" << stats.triangles_culled << " culled), "
                << stats.traversal.tiles_visited << " tiles (" << stats.traversal.tiles_rejected << " rejected, "
                << stats.traversal.tiles_accepted << " accepted, " << stats.traversal.tiles_partial
                << " partial), " << stats.traversal.pixel_tests << " pixel tests, " << stats.traversal.fragments
                << " fragments, crc32 " << crc32_hex(stats.framebuffer_crc32) << ", " << stats.wall_seconds << " s\n";
    }
  });
}

}  // namespace rastsim::app
