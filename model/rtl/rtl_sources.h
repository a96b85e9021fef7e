// SPDX-License-Identifier: Apache-2.0
// The Verilog of rtl/rast_*.sv compiled into the binary (model/rtl/embed_rtl.cmake writes
// rtl_sources.cpp at build time and rewrites it when a source changes), so a tool that
// needs the RTL text itself (Yosys, for `rastsim area`) never reads the source tree.
#pragma once

#include <string_view>
#include <vector>

namespace rastsim {

struct RtlSource {
  std::string_view name;  // file name, e.g. "rast_top.sv"
  std::string_view text;  // its contents
};

// Every rtl/rast_*.sv, sorted by name.
const std::vector<RtlSource>& rtl_sources();

}  // namespace rastsim
