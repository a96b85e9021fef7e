// SPDX-License-Identifier: Apache-2.0
// rastsim_export_rtl: the build's RTL parameter exporter, a tiny stand-alone tool so
// the build can generate rast_params.vh before the rastsim tool itself exists.
// `rastsim export-rtl` (app/cmd_export_rtl.cpp) calls the same function.
//
//   rastsim_export_rtl CONFIG.toml OUT.vh
#include <fstream>
#include <iostream>

#include "config/config.h"
#include "rtl/rtl_params.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: rastsim_export_rtl CONFIG.toml OUT.vh\n";
    return 2;
  }
  try {
    rastsim::Config cfg;
    cfg.load_file(argv[1]);
    cfg.validate();
    const std::string text = rastsim::rtl_params_verilog(rastsim::rtl_params_from_config(cfg), argv[1]);
    // Rewrite only on change, so an unchanged config does not re-run Verilator.
    std::ifstream old(argv[2]);
    const std::string prev((std::istreambuf_iterator<char>(old)), std::istreambuf_iterator<char>());
    if (prev == text) return 0;
    std::ofstream os(argv[2]);
    os << text;
    if (!os) throw std::runtime_error(std::string(argv[2]) + ": write failed");
  } catch (const std::exception& e) {
    std::cerr << "rastsim_export_rtl: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
