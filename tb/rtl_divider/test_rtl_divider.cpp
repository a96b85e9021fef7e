// SPDX-License-Identifier: Apache-2.0
// rast_divider: the circuit (RAST_DIVIDER_STEPS: the pipelined restoring steps Yosys
// synthesises) and the verilated models' simulation form (the quotient computed at entry
// with 64-bit divisions, then delayed) against the exact quotient floor((2 num + den) /
// (2 den)) in 128-bit integers, cycle for cycle: random operands within the divider's
// contract (den > 0, quotient < 2^QW) with their extremes mixed in, random valid_i, and
// random en_i stalls. After every clock edge, q_o of both forms must hold the quotient
// of the wanted division that entered Latency en_i cycles before.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <type_traits>
#include <vector>

#include "Vrast_divider_chunk1_sim.h"
#include "Vrast_divider_chunk1_steps.h"
#include "Vrast_divider_chunks3_sim.h"
#include "Vrast_divider_chunks3_steps.h"
#include "Vrast_divider_default_depth_sim.h"
#include "Vrast_divider_default_depth_steps.h"
#include "Vrast_divider_desktop_color_sim.h"
#include "Vrast_divider_desktop_color_steps.h"
#include "Vrast_divider_desktop_depth_sim.h"
#include "Vrast_divider_desktop_depth_steps.h"
#include "Vrast_divider_embedded_depth_sim.h"
#include "Vrast_divider_embedded_depth_steps.h"
#include "Vrast_divider_fallback_sim.h"
#include "Vrast_divider_fallback_steps.h"
#include "Vrast_divider_small_sim.h"
#include "Vrast_divider_small_steps.h"

namespace {

using u128 = unsigned __int128;

// A port of up to 128 bits: CData/SData/IData/QData or a VlWide of 32-bit words.
template <class Port>
void put(Port& port, u128 v) {
  if constexpr (std::is_integral_v<Port>) {
    port = static_cast<Port>(v);
  } else {
    for (size_t w = 0; w < sizeof(Port) / sizeof(EData); ++w) port[w] = static_cast<EData>(w < 4 ? v >> (32 * w) : 0);
  }
}

template <class Port>
u128 get(const Port& port) {
  if constexpr (std::is_integral_v<Port>) {
    return port;
  } else {
    u128 v = 0;
    for (size_t w = 0; w < sizeof(Port) / sizeof(EData) && w < 4; ++w) v |= u128(port[w]) << (32 * w);
    return v;
  }
}

std::string hex(u128 v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "0x%016llx%016llx", static_cast<unsigned long long>(v >> 64),
                static_cast<unsigned long long>(v));
  return buf;
}

struct Widths {
  int num_w, den_w, q_w, latency;
};

// Uniform in [0, hi] (hi < 2^127), the ends one time in eight each.
u128 pick(std::mt19937_64& rng, u128 hi) {
  switch (rng() % 8) {
    case 0: return 0;
    case 1: return hi;
    default: {
      const u128 r = (u128(rng()) << 64) | rng();
      return hi == ~u128(0) ? r : r % (hi + 1);
    }
  }
}

template <class Steps, class Sim>
void check_forms(const Widths& w, int cycles, uint64_t seed) {
  std::printf("NumW %d DenW %d QW %d Latency %d seed %llu\n", w.num_w, w.den_w, w.q_w, w.latency,
              static_cast<unsigned long long>(seed));
  ASSERT_EQ(w.num_w, w.den_w + w.q_w);
  std::mt19937_64 rng(seed);
  Steps steps;
  Sim sim;
  auto edge = [&](bool en, bool valid, u128 num, u128 den) {
    for (int clk = 0; clk < 2; ++clk) {
      steps.clk_i = sim.clk_i = clk;
      steps.en_i = sim.en_i = en;
      steps.valid_i = sim.valid_i = valid;
      put(steps.num_i, num), put(sim.num_i, num);
      put(steps.den_i, den), put(sim.den_i, den);
      steps.eval();
      sim.eval();
    }
  };
  // A few cycles with en_i high and nothing wanted (the interpolator's reset).
  for (int i = 0; i < w.latency + 2; ++i) edge(true, false, 0, 1);

  std::vector<std::optional<u128>> entered;  // per en_i edge: the wanted quotient
  int checked = 0;
  for (int c = 0; c < cycles; ++c) {
    const bool en = rng() % 5 != 0;
    const bool valid = rng() % 10 < 7;
    const u128 den = 1 + pick(rng, (u128(1) << w.den_w) - 2);
    // The contract q < 2^QW: 2 num + den < 2 den 2^QW.
    const u128 num_max = ((den << (w.q_w + 1)) - den - 1) / 2;
    const u128 num = pick(rng, num_max);
    edge(en, valid, num, den);
    if (en) entered.push_back(valid ? std::optional<u128>((2 * num + den) / (2 * den)) : std::nullopt);
    // After the k-th en_i edge q_o holds what entered on edge k - Latency + 1.
    if (entered.size() < size_t(w.latency)) continue;
    const std::optional<u128>& want = entered[entered.size() - size_t(w.latency)];
    if (!want) continue;
    ++checked;
    ASSERT_EQ(hex(get(steps.q_o)), hex(*want)) << "circuit form, cycle " << c;
    ASSERT_EQ(hex(get(sim.q_o)), hex(*want)) << "simulation form, cycle " << c;
  }
  EXPECT_GT(checked, cycles / 3);
  steps.final();
  sim.final();
}

constexpr int kCycles = 20000;

// One test a set of rtl/CMakeLists.txt RAST_DIVIDER_SETS: its two models, its widths
// {NumW, DenW, QW, Latency} and a seed.
#define RAST_DIVIDER_TEST(test, set, seed, ...)                                                   \
  TEST(RtlDivider, test) {                                                                        \
    check_forms<Vrast_divider_##set##_steps, Vrast_divider_##set##_sim>({__VA_ARGS__}, kCycles, seed); \
  }

RAST_DIVIDER_TEST(DesktopColor, desktop_color, 1, 50, 42, 8, 12)
RAST_DIVIDER_TEST(DesktopDepth, desktop_depth, 2, 66, 42, 24, 12)
RAST_DIVIDER_TEST(DefaultDepth, default_depth, 3, 72, 48, 24, 6)
RAST_DIVIDER_TEST(EmbeddedDepth, embedded_depth, 4, 46, 30, 16, 8)
RAST_DIVIDER_TEST(OneStage, small, 5, 14, 10, 4, 1)
RAST_DIVIDER_TEST(ThreeDivisionsAQuotient, chunks3, 6, 87, 42, 45, 5)
RAST_DIVIDER_TEST(OneBitADivision, chunk1, 7, 77, 61, 16, 3)
RAST_DIVIDER_TEST(DivisorTooWideForTheSimulationForm, fallback, 8, 78, 62, 16, 3)

}  // namespace
