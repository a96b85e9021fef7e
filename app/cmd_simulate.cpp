// SPDX-License-Identifier: Apache-2.0
// `rastsim simulate`: the SystemC cycle-approximate model on one scene; the same image
// and stats as `render`, plus cycles and per-stage busy/stalled/starved cycles, and on
// request where they went: a timeline (sc/timeline.h) and a tile heatmap (sc/tile_heat.h,
// image/heatmap.h); docs/timeline.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "common.h"
#include "frame_output.h"
#include "estimate/estimate.h"
#include "fidelity/frames.h"
#include "fidelity/run_child.h"
#include "fidelity/sampled.h"
#include "fidelity/tolerance.h"
#include "report/stats_json.h"
#include "sc/scanout.h"
#include "sc/raster_pipeline.h"
#include "scene/scene_io.h"
#include "image/heatmap.h"
#include "image/image_io.h"
#include "util/atomic_file.h"

namespace rastsim::app {

namespace {

// --heatmap-data: every attributed stage's busy cycles per tile, and its cycles of no tile.
nlohmann::json heat_json(const sc::SimResult& r, const std::string& shown) {
  const sc::TileHeat& h0 = r.heat.front();
  nlohmann::json j = {{"tile_size", h0.tile_size}, {"tiles_x", h0.tiles_x}, {"tiles_y", h0.tiles_y},
                      {"width", r.fb.width},       {"height", r.fb.height}, {"shown", shown},
                      {"unit", "busy cycles per tile, row-major"}};
  for (const sc::TileHeat& h : r.heat) {
    uint64_t busy = 0;
    for (const auto& s : r.stages)
      if (s.name == h.stage) busy = s.busy;
    j["stages"][h.stage] = {{"busy", busy}, {"unattributed", h.unattributed}, {"tiles", h.cycles}};
  }
  return j;
}

// The heatmap of one stage or of all four summed.
void write_heatmap(const sc::SimResult& r, const std::string& stage, const std::string& path) {
  TileGrid g{r.heat.front().tile_size, r.heat.front().tiles_x, r.heat.front().tiles_y,
             std::vector<uint64_t>(r.heat.front().cycles.size(), 0)};
  for (const sc::TileHeat& h : r.heat)
    if (stage == "all" || stage == h.stage)
      for (size_t i = 0; i < g.cycles.size(); ++i) g.cycles[i] += h.cycles[i];
  const std::string title = stage == "all" ? "busy cycles: coarse+fine+interpolate+rop" : "busy cycles: " + stage;
  write_image(draw_heatmap(r.fb, g, title), path);
}

// "2%", "2" (percent) -> 0.02. Anything else, or outside (0, 100), is an error.
double parse_tolerance(const std::string& text) {
  std::string t = text;
  if (!t.empty() && t.back() == '%') t.pop_back();
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(t, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (t.empty() || used != t.size() || !(v > 0 && v < 100))
    throw std::runtime_error("--tolerance: '" + text + "' is not a percentage in (0, 100), e.g. 2%");
  return v / 100;
}

void print_level(const nlohmann::json& j, std::ostream& out) {
  out << "simulate: " << j["cycles"].get<uint64_t>() << " cycles (" << j["fidelity_level"].get<std::string>()
      << " level";
  const bool frames = j.contains("frames_total");  // frame-sampled, or a multi-frame full run
  if (j.contains("cycles_ci_low"))
    out << ", " << j["confidence"].get<double>() * 100 << " % interval [" << j["cycles_ci_low"].get<double>() << ", "
        << j["cycles_ci_high"].get<double>() << "]";
  if (j.contains("cycles_ci_low") || frames)
    out << ", " << j[frames ? "frames_simulated" : "units_simulated"] << " of " << j[frames ? "frames_total" : "units_total"]
        << (frames ? " frames" : " units") << " simulated";
  if (j.contains("cycles_error_bound")) out << ", error bound " << j["cycles_error_bound"].get<double>() * 100 << " %";
  out << "), " << j["wall_seconds"].get<double>() << " s wall\n";
  if (j.contains("fidelity_reason")) out << "  " << j["fidelity_reason"].get<std::string>() << "\n";
}

// --heatmap-stage: "all" or a stage whose busy cycles are attributed to tiles.
std::vector<std::string> heat_stage_choices() {
  std::vector<std::string> names = {"all"};
  for (const StageInfo& s : kStages)
    if (s.tile_heat) names.emplace_back(s.name);
  return names;
}

// --sample and --tolerance: a level below the full SystemC run answers (docs/fidelity.md).
void run_level_mode(const SimulateOptions& o, const ArchParams& arch) {
  const double tol = o.tolerance.empty() ? 0 : parse_tolerance(o.tolerance);
  for (const std::string* p : {&o.out_path, &o.vcd_path, &o.timeline_path, &o.heatmap_path,
                               &o.heatmap_data_path, &o.frag_path, &o.mem_trace_path})
    if (!p->empty())
      throw std::runtime_error(std::string(o.sample ? "--sample" : "--tolerance") +
                               " makes no image, VCD, timeline, heatmap or fragment stream: drop " + *p);
  check_writable(o.stats_path);
  const Scene scene = load_scene(o.scene_path, arch.placement);
  nlohmann::json j;
  if (o.sample) {
    j = fidelity::simulate_sampled(scene, arch, *o.sample, o.seed).to_json();
  } else {
    bool full = false;
    std::string reason;
    j = fidelity::choose_level(scene, arch, tol, o.seed, full, reason);
    if (full) {
      const sc::SimResult r = sc::simulate_scene(scene, arch);
      j = {{"fidelity_level", "systemc"}, {"cycles", r.cycles},  {"cycles_error_bound", 0.0},
           {"fidelity_reason", reason},   {"wall_seconds", r.sim_wall_seconds}};
      if (const size_t n = fidelity::frame_spans(scene.commands).size(); n > 1)
        j.update({{"frames_total", n}, {"frames_simulated", n}});  // every frame in detail
    }
    j["tolerance"] = tol;
  }
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, arch.placement.camera);
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  print_level(j, summary_stream(o.stats_path, o.quiet));
}

// The recorders and test hooks of a full run, from the options. The fragment stream goes
// to a temporary renamed into place only when the whole run succeeded (util/atomic_file.h).
sc::SimOptions sim_options(const SimulateOptions& o, std::unique_ptr<AtomicFile>& frag_file) {
  sc::SimOptions sim;
  sim.stall_seed = o.seed;
  sim.stall_probability = o.stall_probability;
  if (!o.frag_path.empty()) {
    frag_file = std::make_unique<AtomicFile>(o.frag_path);
    sim.on_fragment = [os = &frag_file->stream()](const Fragment& f) { *os << fragment_trace_line(f) << '\n'; };
  }
  sim.vcd_path = o.vcd_path;
  sim.timeline_path = o.timeline_path;
  sim.mem_trace_path = o.mem_trace_path;
  if (o.timeline_max_events) sim.timeline_max_events = o.timeline_max_events;
  sim.heatmap = !o.heatmap_path.empty() || !o.heatmap_data_path.empty();
  return sim;
}

}  // namespace

void run_simulate_command(const SimulateOptions& o) {
  const ArchParams arch = resolve_arch(o.config, o.scene_path);
  if (o.sample && !o.tolerance.empty()) throw std::runtime_error("--sample and --tolerance exclude each other");
  if (o.sample && !(*o.sample > 0 && *o.sample <= 1)) {
    std::ostringstream got;
    got << *o.sample;
    throw std::runtime_error("--sample: the fraction F must be in (0, 1], got " + got.str());
  }
  check_one_stdout({{"--stats", o.stats_path}, {"--heatmap-data", o.heatmap_data_path}});
  if (o.frame_sample) return run_simulate_frame_sample(o, arch);
  if (!o.frames.empty() && (o.sample || !o.tolerance.empty()))
    throw std::runtime_error("--frames excludes --sample and --tolerance");
  if (o.sample || !o.tolerance.empty()) return run_level_mode(o, arch);
  if (!o.frames.empty() || (!o.out_path.empty() && fidelity::is_frame_pattern(o.out_path)))
    return run_simulate_frames(o, arch);
  std::unique_ptr<AtomicFile> frag_file;
  sc::SimOptions sim = sim_options(o, frag_file);
  FrameStarts frame_starts;  // a multi-frame trace's frames (frames[])
  record_frame_starts(sim, frame_starts);
  // Fails before a long simulation, not after it, when an output cannot be written.
  for (const std::string* p :
       {&o.out_path, &o.stats_path, &o.timeline_path, &o.heatmap_path, &o.heatmap_data_path, &o.mem_trace_path})
    check_writable(*p);
  for (const std::string* p : {&o.out_path, &o.heatmap_path})
    if (!p->empty()) check_image_path(*p);
  // The scene streamed in bounded batches while the simulation runs (memory does not grow
  // with the file); --sample and --tolerance above still load it whole.
  const sc::SimResult r = sc::simulate_stream(o.scene_path, arch, sim);
  if (!o.out_path.empty()) write_image(r.fb, o.out_path);
  nlohmann::json j = r.to_json();
  j["fidelity_level"] = "systemc";
  add_frames_of_run(j, o, arch, frame_starts, r.cycles);
  j["config"] = arch.config.source_name();
  j["scene"] = o.scene_path;
  j["provenance"] = provenance(o.config, arch.config, o.scene_path);
  add_obj_ignored(j, o.scene_path, arch.placement.camera);
  if (!o.timeline_path.empty())
    j["timeline"] = {{"events", r.timeline.events},
                     {"bytes", r.timeline.bytes},
                     {"resolution_cycles", r.timeline.resolution_cycles}};
  if (!o.heatmap_path.empty()) write_heatmap(r, o.heatmap_stage, o.heatmap_path);
  if (!o.heatmap_data_path.empty()) write_json(o.heatmap_data_path, heat_json(r, o.heatmap_stage));
  // Did the frame finish before scan-out needed it? The analytic deadline of the timed
  // scan-out (model/sc/scanout.h; its simulation agrees with it, tb/scanout), at the
  // configured core and pixel clocks. A second SystemC elaboration is not possible in
  // this process, so the scan-out module itself runs in `rastsim scanout`; with
  // memory.model = "dram" the line fetch ran in this simulation as a memory client
  // (scanout_underrun_lines).
  try {
    const ScanoutParams sp = scanout_params(DisplayParams::resolve(arch.config), arch.timing.core_mhz);
    const uint64_t deadline = scanout_deadline_cycles(sp);
    j["frame_time_cycles"] = r.cycles;
    j["frame_deadline_cycles"] = deadline;
    j["frame_deadline_met"] = r.cycles <= deadline;
    if (j.contains("frames"))  // a multi-frame trace: each frame's cycles against the same deadline
      for (auto& f : j["frames"]) f["deadline_met"] = f["cycles"].get<uint64_t>() <= deadline;
  } catch (const std::exception& e) {
    j["frame_deadline_error"] = e.what();
  }
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  if (frag_file) frag_file->commit();
  const sc::StageReport* bottleneck = &r.stages.front();
  for (const auto& s : r.stages)
    if (s.busy > bottleneck->busy) bottleneck = &s;
  summary_stream(o.stats_path, o.quiet)
      << "simulate: " << r.cycles << " cycles (lower bound " << r.cycles_lower_bound << ", busiest stage "
      << bottleneck->name << " " << bottleneck->busy << "), " << triangles_summary(r.render) << ", "
      << r.render.traversal.tiles_visited << " tiles, " << r.render.traversal.fragments << " fragments, crc32 "
      << crc32_hex(r.render.framebuffer_crc32) << ", " << r.sim_wall_seconds << " s wall, "
      << j["simulated_cycles_per_second"].get<double>() << " cycles/s\n";
}

void register_simulate(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate", "Run a scene through the SystemC cycle-approximate pipeline model");
  static SimulateOptions o;
  add_config_options(cmd, o.config);
  add_scene_option(cmd, o.scene_path);
  cmd->add_option("-o,--output", o.out_path,
                  "Image to write: .png or .ppm (bit-identical to `render`); out_%04d.png: one image a frame of a "
                  "multi-frame trace (the reference model's, whose last equals this run's)");
  add_frames_option(cmd, o.frames);
  cmd->add_option_function<double>(
      "--frame-sample", [](double f) { o.frame_sample = f; },
      "Frame-sampled level (multi-frame traces): simulate the first and the last frame and ceil(F x the rest) "
      "representatives (strata by the frames' analytic bottleneck stage, at least 2 a stratum; equal-count "
      "clusters on its busy cycles, deterministic), estimate the rest by ratio; stats fidelity_level = frame-sampled, frames_total, frames_simulated, cycles, "
      "cycles_error_bound, cycles_ci_low/high (95 %; docs/fidelity.md, Frame sampling)")
      ->type_name("F");
  cmd->add_option("--stats", o.stats_path,
                  "Write the stats as JSON ('-' for stdout): render's, plus cycles, cycles_lower_bound, "
                  "stages.<stage>.{busy,stalled,starved}, sim_wall_seconds, simulated_cycles_per_second; with "
                  "memory.model = \"dram\" also dram_row_hit_rate, dram_bandwidth_utilisation, memory.dram.*, "
                  "memory.clients.<client>.*, and the display's line fetch as client scanout, reading the shown "
                  "frame from the same DRAM during the run: memory.clients.scanout.*, scanout_underrun_lines "
                  "(docs/stats.md, docs/scanout.md)");
  cmd->add_option("--vcd", o.vcd_path, "Write a VCD of every FIFO's occupancy and every stage's state "
                                      "(0 starved, 1 busy, 2 stalled); 1 ns = 1 cycle");
  cmd->add_option("--timeline", o.timeline_path,
                  "Write the stages' busy/stalled/starved intervals and the FIFOs' occupancy as Chrome/Perfetto "
                  "trace-event JSON (open in ui.perfetto.dev or chrome://tracing; 1 us shown = 1 cycle)");
  cmd->add_option("--timeline-max-events", o.timeline_max_events,
                  "Above this many events the timeline is merged into power-of-two cycle buckets (sums stay exact)")
      ->check(CLI::Range(uint64_t{1000}, uint64_t{1} << 40))
      ->default_val(sc::SimOptions{}.timeline_max_events);
  cmd->add_option("--heatmap", o.heatmap_path,
                  "Write a PNG of the busy cycles each screen tile cost, over the dimmed frame, with a colour bar");
  cmd->add_option("--heatmap-stage", o.heatmap_stage, "Stage the heatmap shows (default all four summed)")
      ->check(CLI::IsMember(heat_stage_choices()));
  cmd->add_option("--heatmap-data", o.heatmap_data_path,
                  "Write the per-tile busy cycles of every attributed stage as JSON ('-' for stdout)");
  cmd->add_option("--mem-trace", o.mem_trace_path,
                  "Write every DRAM request of every memory client in DRAMsim3's trace format "
                  "('0x<address> READ|WRITE <DRAM clock>', one burst a line; replay with `rastsim dram-replay`, "
                  "DRAMsim3, DRAMSys or Ramulator); needs memory.model = \"dram\"");
  cmd->add_option("--fragments", o.frag_path,
                  "Write every fragment leaving interpolation, one 'x y z r g b' line each (as `render`)");
  cmd->add_option("--stall-probability", o.stall_probability,
                  "Probability that a FIFO write is delayed by 1..8 extra cycles (testing; 0 = off)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option_function<double>(
      "--sample", [](double f) { o.sample = f; },
      "Sampled level: simulate a stratified random fraction F (0 < F <= 1) of the triangle batches and "
      "extrapolate cycles with a 95 % interval (stats cycles, cycles_ci_low, cycles_ci_high; no image, "
      "-o is an error; docs/fidelity.md)")
      ->type_name("F");
  cmd->add_option("--seed", o.seed,
                  "Seed of every random choice of the run: --stall-probability's stalls, --sample's and "
                  "--tolerance's batches (the same seed replays the run)")
      ->capture_default_str();
  for (const char* old_name : {"--stall-seed", "--sample-seed"})  // the names before --seed, still read
    cmd->add_option(old_name, o.seed, "Old name of --seed")->group("");
  cmd->add_option("--tolerance", o.tolerance,
                  "Answer with the cheapest level whose bound or 95 % interval is within P of the cycles, e.g. 2%: "
                  "analytic, else sampled (a multi-frame trace of 4 frames or more: frame-sampled, the smallest F "
                  "its pilot predicts, with frames_total and frames_simulated), else the full SystemC run (stats "
                  "fidelity_level, cycles, cycles_error_bound, fidelity_reason; no image; docs/fidelity.md)");
  add_quiet_flag(cmd, o.quiet, "the summary line");
  cmd->callback([] { run_simulate_command(o); });
}

}  // namespace rastsim::app

// libsystemc.so defines main() and refers to sc_main(); rastsim has its own main() and
// starts the simulation from simulate_scene(), so this is never called.
extern "C" int sc_main(int, char*[]) { return 1; }
