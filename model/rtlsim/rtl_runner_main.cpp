// SPDX-License-Identifier: Apache-2.0
// rast_runner: one on-demand RTL model (rtl_cache.h) as a program of its own. rastsim
// writes this file into the model's cache project, which verilates rast_top with the
// config's rast_params.vh as Vrast_top (rast_params.inc: the same values, compiled in
// below) and links rastsim's testbench libraries; `rastsim cosim` runs it as a child:
//
//   rast_runner REQUEST.json RESULT.json
//     REQUEST: the config (every value and its origin), the scene's file and command
//              count, the options (cosim_setup.h, runner_request)
//     RESULT:  the CosimResult (cosim.h's to_json), or {"error": "..."}
//
// A process of its own keeps one Verilator runtime a process and lets a crash of the
// model end this run only (a sweep goes on).
#include <exception>
#include <fstream>
#include <iostream>

#include "Vrast_top.h"
#include "rtlsim/cosim_driver.h"
#include "rtlsim/cosim_setup.h"
#include "scene/scene_io.h"
#include "scene/scene_params.h"

int main(int argc, char** argv) {
  using namespace rastsim;
  using namespace rastsim::rtlsim;
  if (argc != 3) {
    std::cerr << "usage: rast_runner REQUEST.json RESULT.json (run by rastsim cosim)\n";
    return 2;
  }
  nlohmann::json out;
  try {
    // What this model was built with (the cache key's parameter set).
    const RtlParams built = rtl_params_from_values(
#include "rast_params.inc"
    );
    std::ifstream is(argv[1]);
    if (!is) throw std::runtime_error(std::string(argv[1]) + ": cannot read the request");
    const RunnerRequest q = read_runner_request(nlohmann::json::parse(is));
    const ArchParams arch = resolve_for_scene(q.config, q.scene);  // this process's entry: the config resolved once
    const RtlParams wanted = cosim_wanted_params(arch, q.options);
    std::string why;
    if (!rtl_params_compatible(built, wanted, &why))
      throw std::runtime_error(std::string(argv[0]) + " cannot run this config: " + why);
    const Scene scene = load_scene(q.scene, arch.placement);
    if (scene.commands.size() != q.scene_commands)
      throw std::runtime_error(q.scene + ": has " + std::to_string(scene.commands.size()) + " commands, rastsim read " +
                               std::to_string(q.scene_commands) + " (did the file change?)");
    TbSetup s;
    CosimResult r;
    cosim_setup(scene, arch, q.options, built, s, r);
    run_rtl<Vrast_top>(s, r);
    out = r;
  } catch (const std::exception& e) {
    out = {{"error", e.what()}};
  }
  std::ofstream os(argv[2]);
  os << out.dump() << "\n";
  return os ? 0 : 1;
}
