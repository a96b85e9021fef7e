// SPDX-License-Identifier: Apache-2.0
// `rastsim estimate`: the analytic fidelity level (docs/estimate.md). The timed model's
// per-stage busy cycles from the reference model's geometry, a lower and an upper bound
// on its cycle count and a point estimate, without event simulation.
#include <iostream>
#include <string>

#include "common.h"
#include "frame_output.h"
#include "estimate/estimate.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"

namespace rastsim::app {

void run_estimate_command(const EstimateOptions& o) {
  const ArchParams arch = resolve_arch(o.config, o.scene_path);
  const Scene whole = load_scene(o.scene_path, arch.placement);
  FrameOutput out(o.frames, "");
  const std::vector<fidelity::FrameSpan> spans = fidelity::frame_spans(whole.commands);
  out.range = fidelity::check_frame_range(out.range, spans.size());
  // --frames A:B: the range with the viewport and scissor before it (the estimate does not
  // depend on the framebuffer's contents: the ROP's work follows from the coverage alone).
  const fidelity::FrameSlice slice = fidelity::slice_frames(whole, spans, out.range);
  const Scene& scene = out.range.given ? slice.scene : whole;
  EstimateResult r;
  std::vector<fidelity::FrameWork> work = fidelity::frame_work(scene, arch, &r);
  if (out.range.given && slice.prefix > 0) work.erase(work.begin());
  if (spans.size() > 1 || out.range.given) {
    out.frames_seen = spans.size();
    for (size_t k = 0; k < work.size(); ++k) {
      nlohmann::json f = {{"frame", out.range.first + k}, {"line", spans[out.range.first + k].line},
                          {"triangles_in", work[k].triangles}, {"fragments", work[k].fragments},
                          {"bottleneck_busy", work[k].bottleneck()}};
      fidelity::add_frame_work(f, work[k]);
      out.frames.push_back(f);
    }
  }
  nlohmann::json j = r.to_json();
  out.add_to(j);
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, arch.placement.camera);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  size_t busiest = 0;
  for (size_t s = 0; s < r.stages.size(); ++s)
    if (r.stages[s].busy > r.stages[busiest].busy) busiest = s;
  summary_stream(o.stats_path, o.quiet)
      << "estimate: " << r.cycles_estimate << " cycles (lower bound " << r.cycles_lower_bound << ", upper bound "
      << (r.has_upper_bound() ? std::to_string(r.cycles_upper_bound) : std::string("none with memory.model = dram"))
      << ", busiest stage " << kStages[busiest].name << " " << r.stages[busiest].busy << "), "
      << triangles_summary(r.render) << ", " << r.render.traversal.tiles_visited << " tiles, "
      << r.render.traversal.fragments << " fragments, " << r.wall_seconds << " s wall\n";
}

void register_estimate(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "estimate", "Bound and estimate the SystemC model's cycles analytically, without simulating (docs/estimate.md)");
  static EstimateOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("--stats", o.stats_path,
                  "Write the stats as JSON ('-' for stdout): cycles_lower_bound (stage_lower_bound, "
                  "bandwidth_lower_bound), cycles_upper_bound (null with memory.model = \"dram\"), "
                  "cycles_estimate, wall_seconds, stages.<stage>.busy, the geometry counters, and with "
                  "memory.model = \"dram\" dram_bytes_read, dram_bytes_written, dram_peak_bytes_per_cycle, "
                  "dram_lower_bound (docs/estimate.md)");
  add_frames_option(cmd, o.frames);
  add_quiet_flag(cmd, o.quiet, "the summary line");
  cmd->callback([] { run_estimate_command(o); });
}

}  // namespace rastsim::app
