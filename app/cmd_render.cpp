// SPDX-License-Identifier: Apache-2.0
// `rastsim render`: the reference model on one scene; image, stats, fragment trace.
#include <fstream>
#include <iostream>
#include <thread>

#include "common.h"
#include "frame_output.h"
#include "ref/pipeline.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"
#include "image/image_io.h"
#include "config/raster_state_config.h"
#include "util/atomic_file.h"

namespace rastsim::app {

namespace {
constexpr size_t kSceneBatchCommands = 4096;  // commands parsed ahead of the pipeline
}  // namespace

void run_render_command(const RenderOptions& o) {
  const ArchParams params = resolve_arch(o.config, o.scene_path);
  for (const std::string* p : {&o.out_path, &o.stats_path}) check_writable(*p);  // before the run, creating nothing
  FrameOutput frames(o.frames, o.out_path);  // checks -o's name (a pattern: its first frame's)
  RenderStats stats;
  std::unique_ptr<AtomicFile> frag_file;  // renamed into place only when the run succeeds
  FragmentSink sink;
  if (!o.frag_path.empty()) {
    frag_file = std::make_unique<AtomicFile>(o.frag_path);
    sink = [os = &frag_file->stream()](const Fragment& f) { *os << fragment_trace_line(f) << '\n'; };
  }
  // The scene streamed in bounded batches (scene_io.h): memory does not grow with the file.
  // Split at each `frame` (fidelity/frames.h): a single-frame scene runs as one batch stream.
  const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  fidelity::FrameRenderer renderer(
      params, stats, [&](const fidelity::FrameCounts& c, const Framebuffer& fb) { frames.on_frame(c, fb); }, threads,
      sink);
  renderer.stop_at(frames.range.last);
  uint64_t done = 0;
  bool drawing = false;  // an error of the pipeline itself, not of the reader, passes unchanged
  try {
    const CommandBatchFn draw = [&](std::vector<Command>& batch) {
      drawing = true;
      renderer.feed(batch);
      drawing = false;
      done += batch.size();
    };
    if (threads > 1) stream_scene_ahead(o.scene_path, params.placement, kSceneBatchCommands, kSceneBatchesAhead, draw);
    else stream_scene(o.scene_path, params.placement, kSceneBatchCommands, draw);
  } catch (const SceneError& e) {
    if (drawing || done == 0) throw;
    throw SceneError(std::string(e.what()) + " (after " + std::to_string(done) +
                     " commands of the scene were drawn; no image or stats written)");
  }
  const Framebuffer fb = renderer.finish();
  frames.check_done();
  if (!o.out_path.empty() && !frames.pattern) write_image(fb, o.out_path);  // the last frame run
  nlohmann::json j = to_json(stats);
  frames.add_to(j);
  j["config"] = params.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, params.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, params.placement.camera);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  if (frag_file) frag_file->commit();
  std::ostream& out = summary_stream(o.stats_path, o.quiet);
  out << "render: " << triangles_summary(stats) << ", " << stats.traversal.tiles_visited << " tiles ("
      << stats.traversal.tiles_rejected << " rejected, " << stats.traversal.tiles_accepted << " accepted, "
      << stats.traversal.tiles_partial << " partial), " << stats.traversal.pixel_tests << " pixel tests, "
      << stats.traversal.fragments << " fragments, ";
  if (stats.samples > 1)
    out << stats.samples << " samples (" << (stats.aa_mode == AaMode::Ssaa ? "ssaa" : "msaa") << ", "
        << stats.traversal.samples_covered << " covered), ";
  out << "crc32 " << crc32_hex(stats.framebuffer_crc32) << ", " << stats.wall_seconds << " s\n";
}

void register_render(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a scene with the bit-exact reference model");
  static RenderOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("-o,--output", o.out_path,
                  "Image to write: .png or .ppm (colour buffer, RGB); a name with one integer conversion "
                  "(out_%04d.png) writes one image a frame of a multi-frame trace, a plain name the last frame run");
  add_frames_option(cmd, o.frames);
  cmd->add_option("--stats", o.stats_path, "Write the stats as JSON to this file ('-' for stdout)");
  cmd->add_option("--fragments", o.frag_path,
                  "Write every fragment leaving interpolation, one 'x y z r g b' line each, in pipeline order");
  cmd->add_option("--threads", o.threads,
                  "Rasterize on N threads of this process (default: every core): triangles are binned to screen regions drawn "
                  "in parallel, each pixel's fragments in scene order, so the image, CRC and stats equal "
                  "--threads 1's; the trace is parsed on a thread of its own, ahead of the drawing. "
                  "--fragments (pipeline order) and raster.traversal = scanline draw on one thread")
      ->check(CLI::Range(1, 1024));
  add_quiet_flag(cmd, o.quiet, "the summary line");
  cmd->callback([] { run_render_command(o); });
}

}  // namespace rastsim::app
