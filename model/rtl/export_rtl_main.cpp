// SPDX-License-Identifier: Apache-2.0
// rastsim_export_rtl: the build's RTL parameter exporter, a tiny stand-alone tool so
// the build can generate rast_params.vh before the rastsim tool itself exists.
// `rastsim export-rtl` (app/cmd_export_rtl.cpp) calls the same function.
//
//   rastsim_export_rtl CONFIG.toml OUT.vh OUT.inc
//
// OUT.vh is the Verilog parameter list; OUT.inc the same values as a C++ expression
// (rtl_params_cpp) that the generated registry of verilated models compiles in.
#include <fstream>
#include <iostream>

#include "config/config.h"
#include "rtl/rtl_params.h"

namespace {
// Rewrites a file only when its text changes, so an unchanged config re-runs nothing.
void write_if_changed(const std::string& path, const std::string& text) {
  std::ifstream old(path);
  const std::string prev((std::istreambuf_iterator<char>(old)), std::istreambuf_iterator<char>());
  if (prev == text) return;
  std::ofstream os(path);
  os << text;
  if (!os) throw std::runtime_error(path + ": write failed");
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: rastsim_export_rtl CONFIG.toml OUT.vh OUT.inc\n";
    return 2;
  }
  try {
    rastsim::Config cfg;
    cfg.load_file(argv[1]);
    cfg.validate();
    const rastsim::RtlParams p = rastsim::rtl_params_from_config(cfg);
    write_if_changed(argv[2], rastsim::rtl_params_verilog(p, argv[1]));
    write_if_changed(argv[3], "// Generated from " + std::string(argv[1]) + ". Do not edit.\n" +
                                  rastsim::rtl_params_cpp(p) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "rastsim_export_rtl: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
