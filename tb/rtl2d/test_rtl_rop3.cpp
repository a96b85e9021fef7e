// SPDX-License-Identifier: Apache-2.0
// rast_rop3: all 256 codes on random P, S, D against the truth table evaluated per bit, the
// named codes against their Boolean formulas, and reads_d/reads_s against a brute-force
// dependence check over the eight table rows.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>

#include "Vrast_rop3.h"

namespace {

constexpr uint32_t kMask = 0xffffff;  // rast_rop3's Width = 24

uint32_t truth_table(uint8_t code, uint32_t p, uint32_t s, uint32_t d) {
  uint32_t r = 0;
  for (int k = 0; k < 24; ++k) {
    const int row = int((p >> k) & 1) * 4 + int((s >> k) & 1) * 2 + int((d >> k) & 1);
    r |= uint32_t((code >> row) & 1) << k;
  }
  return r;
}

TEST(RtlRop3, All256CodesRandomData) {
  const uint32_t seed = 0x0403;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  Vrast_rop3 dut;
  int checks = 0;
  for (int code = 0; code < 256; ++code) {
    bool dep_d = false, dep_s = false;
    for (int row = 0; row < 8; ++row) {
      dep_d |= ((code >> row) & 1) != ((code >> (row ^ 1)) & 1);
      dep_s |= ((code >> row) & 1) != ((code >> (row ^ 2)) & 1);
    }
    for (int n = 0; n < 200; ++n) {
      const uint32_t p = rng() & kMask, s = rng() & kMask, d = rng() & kMask;
      dut.code_i = uint8_t(code);
      dut.p_i = p;
      dut.s_i = s;
      dut.d_i = d;
      dut.eval();
      ASSERT_EQ(dut.r_o, truth_table(uint8_t(code), p, s, d)) << "code " << code;
      ASSERT_EQ(bool(dut.reads_d_o), dep_d) << "code " << code;
      ASSERT_EQ(bool(dut.reads_s_o), dep_s) << "code " << code;
      switch (code) {
        case 0x00: ASSERT_EQ(dut.r_o, 0u); break;
        case 0xFF: ASSERT_EQ(dut.r_o, kMask); break;
        case 0xF0: ASSERT_EQ(dut.r_o, p); break;
        case 0xCC: ASSERT_EQ(dut.r_o, s); break;
        case 0xAA: ASSERT_EQ(dut.r_o, d); break;
        case 0x33: ASSERT_EQ(dut.r_o, ~s & kMask); break;
        case 0x66: ASSERT_EQ(dut.r_o, s ^ d); break;
        case 0x88: ASSERT_EQ(dut.r_o, s & d); break;
        case 0xEE: ASSERT_EQ(dut.r_o, s | d); break;
        case 0x5A: ASSERT_EQ(dut.r_o, p ^ d); break;
        case 0xC0: ASSERT_EQ(dut.r_o, p & s); break;
        default: break;
      }
      ++checks;
    }
  }
  std::printf("%d pixel checks over 256 codes\n", checks);
}

}  // namespace
