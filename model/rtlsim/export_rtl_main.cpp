// SPDX-License-Identifier: Apache-2.0
// rastsim_export_rtl: the build's RTL parameter exporter, a tiny stand-alone tool that
// runs at configure time (rtl/CMakeLists.txt), before the rastsim tool exists.
// `rastsim export-rtl` (app/cmd_export_rtl.cpp) calls the same functions.
//
//   rastsim_export_rtl CONFIG.toml OUT.vh OUT.inc
//     OUT.vh:  rast_top's parameter header (rtl_params_verilog)
//     OUT.inc: the same parameters as a C++ initializer list (rtl_params_values),
//              compiled into the registry of verilated models (model/rtlsim/CMakeLists.txt)
//   rastsim_export_rtl --scanout CONFIG.toml OUT.vh
//     OUT.vh:  the scan-out top's parameter header (scanout_rtl_params_verilog)
//   rastsim_export_rtl --root ROOT CONFIG.toml OUT.f
//     OUT.f:   a standalone root's parameters (root_rtl_params) as Verilator arguments,
//              one -GName=value a line (tb/rtl_texture verilates its units with them)
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include "config/config.h"
#include "rtlsim/rtl_params.h"

namespace {

// Rewrites `path` only when its text changes, so an unchanged config re-runs neither
// Verilator nor the registry's compilation.
void write_if_changed(const std::string& path, const std::string& text) {
  std::ifstream old(path);
  const std::string prev((std::istreambuf_iterator<char>(old)), std::istreambuf_iterator<char>());
  if (prev == text) return;
  std::ofstream os(path);
  os << text;
  if (!os) throw std::runtime_error(path + ": write failed");
}

}  // namespace

// Each of root_rtl_params(root) as "-GName=value", a line each.
std::string root_args(const std::string& root, const rastsim::ArchParams& arch) {
  const auto params = rastsim::root_rtl_params(root, arch);
  if (params.empty()) throw std::runtime_error("--root " + root + ": a root without config parameters");
  std::string out;
  for (const auto& [name, value] : params) out += "-G" + name + "=" + std::to_string(value) + "\n";
  return out;
}

int main(int argc, char** argv) {
  if (argc == 5 && std::string(argv[1]) == "--root") {
    try {
      rastsim::Config cfg;
      cfg.load_file(argv[3]);
      cfg.validate();
      write_if_changed(argv[4], root_args(argv[2], rastsim::ArchParams::resolve(cfg)));
    } catch (const std::exception& e) {
      std::cerr << "rastsim_export_rtl: error: " << e.what() << "\n";
      return 1;
    }
    return 0;
  }
  const bool scanout = argc == 4 && std::string(argv[1]) == "--scanout";
  if (argc != 4) {
    std::cerr << "usage: rastsim_export_rtl CONFIG.toml OUT.vh OUT.inc\n"
                 "       rastsim_export_rtl --scanout CONFIG.toml OUT.vh\n"
                 "       rastsim_export_rtl --root ROOT CONFIG.toml OUT.f\n";
    return 2;
  }
  try {
    const char* cfg_path = argv[scanout ? 2 : 1];
    rastsim::Config cfg;
    cfg.load_file(cfg_path);
    cfg.validate();
    if (scanout) {
      write_if_changed(argv[3], rastsim::scanout_rtl_params_verilog(rastsim::scanout_rtl_params(rastsim::ArchParams::resolve(cfg), rastsim::DisplayParams::resolve(cfg)), cfg_path));
      return 0;
    }
    const rastsim::RtlParams p = rastsim::rtl_params(rastsim::ArchParams::resolve(cfg));
    write_if_changed(argv[2], rastsim::rtl_params_verilog(p, cfg_path));
    write_if_changed(argv[3], rastsim::rtl_params_values(p) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "rastsim_export_rtl: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
