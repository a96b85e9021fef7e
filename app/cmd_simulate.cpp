// SPDX-License-Identifier: Apache-2.0
// `rastsim simulate`: the SystemC cycle-approximate model on one scene; the same image
// and stats as `render`, plus cycles and per-stage busy/stalled/starved cycles.
#include <cstdio>
#include <fstream>
#include <iostream>

#include "common.h"
#include "report/stats_json.h"
#include "sc/scanout.h"
#include "sc/raster_pipeline.h"
#include "scene/scene_io.h"
#include "display/image_io.h"

namespace rastsim::app {

void run_simulate_command(const SimulateOptions& o) {
  const Config cfg = load_config(o.config);
  const Scene scene = load_scene(o.scene_path, obj_placement(cfg));
  sc::SimOptions sim;
  sim.stall_seed = o.stall_seed;
  sim.stall_probability = o.stall_probability;
  std::ofstream frag_os;
  if (!o.frag_path.empty()) {
    frag_os.open(o.frag_path);
    if (!frag_os) throw std::runtime_error(o.frag_path + ": cannot open for writing");
    sim.on_fragment = [&](const Fragment& f) { frag_os << fragment_trace_line(f) << '\n'; };
  }
  sim.vcd_path = o.vcd_path;
  const sc::SimResult r = sc::simulate_scene(scene, cfg, sim);
  if (!o.out_path.empty()) write_image(r.fb, o.out_path);
  nlohmann::json j = r.to_json();
  j["config"] = cfg.source_name();
  j["scene"] = o.scene_path;
  // Did the frame finish before scan-out needed it? The analytic deadline of the timed
  // scan-out (model/sc/scanout.h; its simulation agrees with it, tb/scanout), at the
  // configured core and pixel clocks. A second SystemC elaboration is not possible in
  // this process, so the scan-out module itself runs in `rastsim scanout`.
  try {
    const sc::ScanoutParams sp = sc::scanout_params_from_config(cfg, cfg.get_float("clock.core_mhz"));
    const uint64_t deadline = sc::scanout_deadline_cycles(sp);
    j["frame_time_cycles"] = r.cycles;
    j["frame_deadline_cycles"] = deadline;
    j["frame_deadline_met"] = r.cycles <= deadline;
  } catch (const std::exception& e) {
    j["frame_deadline_error"] = e.what();
  }
  if (!o.stats_path.empty()) write_json(o.stats_path, j);
  if (!o.quiet) {
    const sc::StageReport* bottleneck = &r.stages.front();
    for (const auto& s : r.stages)
      if (s.busy > bottleneck->busy) bottleneck = &s;
    std::cout << "simulate: " << r.cycles << " cycles (lower bound " << r.cycles_lower_bound << ", busiest stage "
              << bottleneck->name << " " << bottleneck->busy << "), " << r.render.triangles_in << " triangles, "
              << r.render.traversal.tiles_visited << " tiles, " << r.render.traversal.fragments
              << " fragments, crc32 " << crc32_hex(r.render.framebuffer_crc32) << ", " << r.sim_wall_seconds << " s wall, "
              << j["simulated_cycles_per_second"].get<double>() << " cycles/s\n";
  }
}

void register_simulate(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate", "Run a scene through the SystemC cycle-approximate pipeline model");
  static SimulateOptions o;
  add_config_options(cmd, o.config);
  cmd->add_option("--scene,-s", o.scene_path, "Scene: a trace (.trace) or a Wavefront OBJ (.obj)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o.out_path, "Image to write: .png or .ppm (bit-identical to `render`)");
  cmd->add_option("--stats", o.stats_path,
                  "Write the stats as JSON ('-' for stdout): render's, plus cycles, cycles_lower_bound, "
                  "stages.<stage>.{busy,stalled,starved}, sim_wall_seconds, simulated_cycles_per_second");
  cmd->add_option("--vcd", o.vcd_path, "Write a VCD of every FIFO's occupancy and every stage's state "
                                      "(0 starved, 1 busy, 2 stalled); 1 ns = 1 cycle");
  cmd->add_option("--fragments", o.frag_path,
                  "Write every fragment leaving interpolation, one 'x y z r g b' line each (as `render`)");
  cmd->add_option("--stall-seed", o.stall_seed, "Seed of the random stall injection (testing)");
  cmd->add_option("--stall-probability", o.stall_probability,
                  "Probability that a FIFO write is delayed by 1..8 extra cycles (testing; 0 = off)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--quiet,-q", o.quiet, "Do not print the summary line");
  cmd->callback([] { run_simulate_command(o); });
}

}  // namespace rastsim::app

// libsystemc.so defines main() and refers to sc_main(); rastsim has its own main() and
// starts the simulation from simulate_scene(), so this is never called.
extern "C" int sc_main(int, char*[]) { return 1; }
