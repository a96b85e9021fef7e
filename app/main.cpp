// SPDX-License-Identifier: Apache-2.0
// rastsim: the command-line front end of the reference, timed and RTL models.
#include <iostream>

#include "common.h"
#include "util/version.h"
#include "util/interrupt.h"

int main(int argc, char** argv) {
  CLI::App app{
      "rastsim: cycle-approximate GPU rasterizer model.\n"
      "Bit-exact reference rendering (render), the SystemC timed model (simulate, sweep) and its\n"
      "analytic bounds (estimate), the Verilog RTL in Verilator (cosim) and its area in Yosys (area),\n"
      "scan-out through video timing and a DAC (scanout, monitor). Every command takes --config FILE\n"
      "and --set section.key=value; see `rastsim COMMAND --help` and `rastsim config --doc`."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rastsim ") + rastsim::rastsim_version(),
                       "Print the version (git describe of the sources at build time) and exit");
  app.set_help_all_flag("--help-all", "Help for every command");
  rastsim::app::register_config(app);
  rastsim::app::register_render(app);
  rastsim::app::register_simulate(app);
  rastsim::app::register_estimate(app);
  rastsim::app::register_sweep(app);
  rastsim::app::register_cosim(app), rastsim::app::register_export_rtl(app), rastsim::app::register_area(app);
  rastsim::app::register_scanout(app), rastsim::app::register_monitor(app);
  rastsim::app::register_fit(app);
  rastsim::app::register_coverage_error(app);
  rastsim::app::register_recip_grid(app);
  rastsim::app::register_dram_replay(app);
  rastsim::app::register_import_apitrace(app);
  rastsim::install_interrupt_handler();  // Ctrl-C: children stopped, temporaries removed
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const rastsim::Interrupted& e) {
    std::cerr << "rastsim: " << e.what() << "\n";
    return 128 + e.signal();
  } catch (const std::exception& e) {
    // Every input error (config, scene, I/O) arrives here as one line naming its source.
    std::cerr << "rastsim: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
