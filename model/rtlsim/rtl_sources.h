// SPDX-License-Identifier: Apache-2.0
// Text compiled into the binary (model/rtlsim/embed_rtl.cmake writes it at build time and
// rewrites it when a file changes), so a tool that needs it never reads the source tree:
// - rtl_sources(): the Verilog of rtl/rast_*.sv, for Yosys (`rastsim area`) and for the
//   on-demand models (rtl_cache.h);
// - rtl_build_files(): the rest of an on-demand model's project (rtl_cache.cpp): the lint
//   waivers ("rtl/lint/<name>.vlt"), the shared Verilator arguments
//   ("rtl/rast_verilate.cmake"), the runner's main ("runner/rtl_runner_main.cpp"), and
//   the testbench headers the runner compiles ("key/<name>.h": hashed into the cache key
//   under that name, compiled from the copy written to the project's include/rtlsim/).
#pragma once

#include <string_view>
#include <vector>

namespace rastsim {

struct RtlSource {
  std::string_view name;  // file name, e.g. "rast_top.sv" (rtl_build_files: a relative path)
  std::string_view text;  // its contents
};

// Every rtl/rast_*.sv, sorted by name.
const std::vector<RtlSource>& rtl_sources();
// The other files of an on-demand model's project, sorted by name (above).
const std::vector<RtlSource>& rtl_build_files();

}  // namespace rastsim
