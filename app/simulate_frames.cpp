// SPDX-License-Identifier: Apache-2.0
// `rastsim simulate` on multi-frame scenes: frames[] of a full run, `--frames A:B` (the
// frames before A replayed by the reference model, A.. timed from their framebuffer) and
// the frame-sampled level (`--frame-sample F`, fidelity/frame_sampled.h).
#include <iostream>
#include <stdexcept>

#include "common.h"
#include "fidelity/frame_sampled.h"
#include "frame_output.h"
#include "sc/raster_pipeline.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"
#include "image/image_io.h"

namespace rastsim::app {

void record_frame_starts(sc::SimOptions& sim, FrameStarts& f) {
  sim.on_memory_system = [&f](const MemorySystem& m) { f.memory = &m; };
  sim.on_fetch = [&f](const Command& cmd, size_t triangle, uint64_t cycle) {
    if (cmd.frame_line == 0 || triangle != 0) return;
    f.cycles.push_back(cycle);
    if (f.memory) f.backlog.push_back(f.memory->backlog_cycles(cycle));
  };
  sim.on_rop_state = [&f](const Command& cmd, uint64_t cycle) {
    if (cmd.frame_line > 0) f.rop.push_back(cycle);
  };
}

void add_frames_of_run(nlohmann::json& j, const SimulateOptions& o, const ArchParams& arch, const FrameStarts& f,
                       uint64_t end_cycle) {
  const std::vector<uint64_t>& starts = f.cycles;
  if (starts.empty()) return;  // one frame: no frames[]
  const Scene scene = load_scene(o.scene_path, arch.placement);
  FrameOutput out("", "");
  replay_frames(scene, arch, out);
  const std::vector<fidelity::FrameWork> work = fidelity::frame_work(scene, arch);
  if (out.frames.size() != starts.size() + 1 || work.size() != out.frames.size())
    throw std::logic_error("simulate: the run fetched " + std::to_string(starts.size() + 1) + " frames, the scene has " +
                           std::to_string(out.frames.size()));
  // Each frame's cycles from its start to the next's (fidelity::FrameBoundary), and at
  // command fetch (cycles_fetch): either sums to the run's cycles.
  const fidelity::FrameBoundary b = fidelity::frame_boundary(scene, fidelity::frame_spans(scene.commands), arch);
  if (b == fidelity::FrameBoundary::Rop && f.rop.size() != starts.size())
    throw std::logic_error("simulate: the ROP took " + std::to_string(f.rop.size()) + " frames' first commands of " +
                           std::to_string(starts.size()));
  const std::vector<uint64_t>& at = b == fidelity::FrameBoundary::Rop ? f.rop : starts;
  j["frame_boundary"] = fidelity::frame_boundary_name(b);
  for (size_t k = 0; k < out.frames.size(); ++k) {
    const uint64_t from = k == 0 ? 0 : at[k - 1], to = k < at.size() ? at[k] : end_cycle;
    out.frames[k]["cycles"] = to - from;
    out.frames[k]["cycles_fetch"] = (k < starts.size() ? starts[k] : end_cycle) - (k == 0 ? 0 : starts[k - 1]);
    if (f.memory) out.frames[k]["dram_backlog_cycles"] = k == 0 ? 0 : f.backlog[k - 1];
    fidelity::add_frame_work(out.frames[k], work[k]);
  }
  out.add_to(j);
}

namespace {

// The frames' timed run, from the framebuffer `before` (frames before the range).
sc::SimResult run_range(const Scene& scene, const ArchParams& arch, const FrameOutput& out, const Framebuffer& before,
                        uint64_t seed, double stall_probability, std::vector<uint64_t>& cycles) {
  const std::vector<fidelity::FrameSpan> spans = fidelity::frame_spans(scene.commands);
  const fidelity::FrameSlice slice = fidelity::slice_frames(scene, spans, out.range);
  fidelity::CommandStarts starts;
  sc::SimOptions sim;
  sim.stall_seed = seed;
  sim.stall_probability = stall_probability;
  fidelity::record_command_starts(slice.scene, starts, sim);
  if (out.range.first > 0) sim.initial_fb = &before;
  sc::SimResult r = sc::simulate_scene(slice.scene, arch, sim);
  // The range's frames as the full run's frames[] (its first from its fetch).
  std::vector<fidelity::FrameSpan> timed = fidelity::frame_spans(slice.scene.commands);
  if (slice.prefix > 0) timed.erase(timed.begin());  // the carried viewport and scissor: not a frame
  cycles = fidelity::span_cycles(timed, starts, fidelity::frame_boundary(scene, spans, arch), r.cycles);
  return r;
}

}  // namespace

void run_simulate_frames(const SimulateOptions& o, const ArchParams& arch) {
  for (const std::string* p : {&o.vcd_path, &o.timeline_path, &o.heatmap_path, &o.heatmap_data_path, &o.frag_path,
                               &o.mem_trace_path})
    if (!p->empty()) throw std::runtime_error("--frames and an -o pattern make no VCD, timeline, heatmap, fragment "
                                              "stream or memory trace yet: drop " + *p);
  for (const std::string* p : {&o.out_path, &o.stats_path}) check_writable(*p);
  const Scene scene = load_scene(o.scene_path, arch.placement);
  FrameOutput out(o.frames, o.out_path);
  out.range = fidelity::check_frame_range(out.range, fidelity::frame_spans(scene.commands).size());
  Framebuffer before(arch.raster.fb_width, arch.raster.fb_height, arch.raster.samples);
  replay_frames(scene, arch, out, &before);  // frames[] counts and images (reference model)
  std::vector<uint64_t> cycles;
  const sc::SimResult r = run_range(scene, arch, out, before, o.seed, o.stall_probability, cycles);
  const std::string ref_crc = out.frames.back()["framebuffer_crc32"];
  if (crc32_hex(r.render.framebuffer_crc32) != ref_crc)
    throw std::logic_error("simulate --frames: the SystemC model's last frame (crc32 " +
                           crc32_hex(r.render.framebuffer_crc32) + ") differs from the reference model's (" +
                           ref_crc + ")");
  const std::vector<fidelity::FrameWork> work = fidelity::frame_work(scene, arch);
  uint64_t total = 0;
  for (size_t k = 0; k < out.frames.size(); ++k) {
    out.frames[k]["cycles"] = cycles[k];
    fidelity::add_frame_work(out.frames[k], work[out.range.first + k]);
    total += cycles[k];
  }
  if (!o.out_path.empty() && !out.pattern) write_image(r.fb, o.out_path);
  nlohmann::json j = r.to_json();
  j["cycles_run"] = r.cycles;  // with the carried state commands before the range
  j["cycles"] = total;
  j["fidelity_level"] = "systemc";
  j["frame_boundary"] = fidelity::frame_boundary_name(
      fidelity::frame_boundary(scene, fidelity::frame_spans(scene.commands), arch));
  out.add_to(j);
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  summary_stream(o.stats_path, o.quiet) << "simulate: frames " << out.range.first << ".." << out.range.last - 1
                                        << ": " << total << " cycles, " << out.frames.size() << " frames, crc32 "
                                        << crc32_hex(r.render.framebuffer_crc32) << ", " << r.sim_wall_seconds
                                        << " s wall\n";
}

void run_simulate_frame_sample(const SimulateOptions& o, const ArchParams& arch) {
  if (!(*o.frame_sample > 0 && *o.frame_sample <= 1))
    throw std::runtime_error("--frame-sample: the fraction F must be in (0, 1]");
  for (const std::string* p : {&o.out_path, &o.vcd_path, &o.timeline_path, &o.heatmap_path, &o.heatmap_data_path,
                               &o.frag_path, &o.mem_trace_path})
    if (!p->empty())
      throw std::runtime_error("--frame-sample makes no image, VCD, timeline, heatmap or fragment stream: drop " + *p);
  if (o.sample || !o.tolerance.empty() || !o.frames.empty())
    throw std::runtime_error("--frame-sample excludes --sample, --tolerance and --frames");
  check_writable(o.stats_path);
  const Scene scene = load_scene(o.scene_path, arch.placement);
  const fidelity::FrameSampledResult res = fidelity::simulate_frame_sampled(scene, arch, *o.frame_sample);
  nlohmann::json j = res.to_json();
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  summary_stream(o.stats_path, o.quiet)
      << "simulate: " << j["cycles"].get<uint64_t>() << " cycles (frame-sampled level, "
      << res.confidence * 100 << " % interval [" << res.ci_low << ", " << res.ci_high << "], " << res.frames_simulated
      << " of " << res.frames_total << " frames simulated, error bound "
      << j["cycles_error_bound"].get<double>() * 100 << " %), " << res.wall_seconds << " s wall\n";
}

}  // namespace rastsim::app
