// SPDX-License-Identifier: Apache-2.0
// The fuzz harnesses, one a parser (docs/fuzzing.md). Each takes one input's bytes,
// feeds them to its parser and checks the outcome: the parser's documented error type
// or an accepted result that respects the documented invariants. Anything else is a
// finding (fuzz_common.h): an abort under libFuzzer (fuzz_target.cpp), a thrown Finding
// in the gtest that replays fuzz/corpus and fuzz/regressions with gcc
// (tb/test_parser_regressions.cpp). Crashes and sanitizer reports end either process.
#pragma once

#include <string>
#include <string_view>

namespace rastsim::fuzz {

void trace_one(std::string_view input);   // harness_trace.cpp: traces, plain or gzip/zstd
void obj_one(std::string_view input);     // harness_obj.cpp: OBJ meshes and their placement
void mtl_one(std::string_view input);     // harness_mtl.cpp: MTL material libraries
void config_one(std::string_view input);  // harness_config.cpp: TOML configs and --set
void signal_one(std::string_view input);  // harness_signal.cpp: VCD signal files

// The harness of a target name (trace, obj, mtl, config, signal); nullptr if none.
using Harness = void (*)(std::string_view);
inline Harness harness(const std::string& target) {
  if (target == "trace") return trace_one;
  if (target == "obj") return obj_one;
  if (target == "mtl") return mtl_one;
  if (target == "config") return config_one;
  if (target == "signal") return signal_one;
  return nullptr;
}

}  // namespace rastsim::fuzz
