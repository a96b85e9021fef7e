// SPDX-License-Identifier: Apache-2.0
// The libFuzzer entry point of one target, compiled once per target with
// RASTSIM_FUZZ_TARGET set to its name (fuzz/CMakeLists.txt).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_common.h"
#include "harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const rastsim::fuzz::Harness run = [] {
    rastsim::fuzz::abort_on_finding() = true;
    return rastsim::fuzz::harness(RASTSIM_FUZZ_TARGET);
  }();
  run(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
