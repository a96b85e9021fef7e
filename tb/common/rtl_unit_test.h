// SPDX-License-Identifier: Apache-2.0
// Helpers of the tests of verilated RTL units (tb/rtl_fp32, tb/rtl_recip): the random
// seed, and the clock and reset of a unit with a valid/ready stream (ports clk_i, rst_ni,
// in_valid_i, out_ready_i).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

namespace rastsim::test {

// The random seed: a fixed one by default (ctest draws the same operands every run), the
// environment variable `name`=<n> replays run n, `name`=random draws a new one. Printed,
// as `name`=<seed>, so a failing run can be replayed.
inline uint64_t seed_from_env(const char* name, uint64_t fixed) {
  const char* env = std::getenv(name);
  const std::string text = env ? env : "";
  const uint64_t v = text.empty()       ? fixed
                     : text == "random" ? std::random_device{}()
                                        : std::strtoull(text.c_str(), nullptr, 10);
  std::printf("%s=%llu\n", name, static_cast<unsigned long long>(v));
  return v;
}

// One clock cycle: a falling then a rising edge.
template <class Model>
void clock_cycle(Model& m) {
  m.clk_i = 0, m.eval();
  m.clk_i = 1, m.eval();
}

// Reset with nothing offered and nothing taken, then out of reset (clock low). rst_ni
// goes 1 -> 0 -> 1: Verilator's variables start at 0, so driving it low from there is
// no falling edge and an asynchronous-reset block (always_ff @(negedge rst_ni)) would
// never run, leaving every non-zero reset value unset.
template <class Model>
void reset_stream(Model& m) {
  m.rst_ni = 1, m.in_valid_i = 0, m.out_ready_i = 0, m.clk_i = 0;
  m.eval();
  m.rst_ni = 0, m.eval();
  m.rst_ni = 1, m.eval();
}

}  // namespace rastsim::test
