// SPDX-License-Identifier: Apache-2.0
// `rastsim export-rtl`: the Verilog parameter header of a config (model/rtlsim/rtl_params.h),
// the same text the build's exporter writes for each verilated config.
#include <fstream>
#include <iostream>

#include "common.h"
#include "rtlsim/rtl_params.h"

namespace rastsim::app {

void register_export_rtl(CLI::App& app) {
  auto* cmd = app.add_subcommand("export-rtl", "Write the RTL parameter header (rast_params.vh) of a config");
  static ConfigOptions opts;
  static std::string out_path = "-";
  static bool quiet = false;  // the header is the output: nothing else is printed
  add_config_options(cmd, opts);
  cmd->add_option("-o,--output", out_path, "Header to write ('-' for stdout)");
  add_quiet_flag(cmd, quiet, "anything but the header");
  cmd->callback([] {
    const Config cfg = load_config(opts);
    const std::string text = rtl_params_verilog(rtl_params(ArchParams::resolve(cfg)), cfg.source_name());
    if (out_path == "-") {
      std::cout << text;
      return;
    }
    std::ofstream os(out_path);
    os << text;
    if (!os) throw std::runtime_error(out_path + ": write failed");
  });
}

}  // namespace rastsim::app
