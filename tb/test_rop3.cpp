// SPDX-License-Identifier: Apache-2.0
// ROP3 (ref/2d/rop3.h): all 256 codes against the truth table evaluated one bit at a time
// (the notes' definition), on random P, S, D; the named codes against their boolean
// formulas (hand-written); which codes read S and D, by brute force over the table.
#include <gtest/gtest.h>

#include <random>

#include "ref/2d/rop3.h"

namespace rastsim {
namespace {

// Bit by bit: look the (p, s, d) triple of each bit position up in the code.
uint8_t rop3_by_table(uint8_t code, uint8_t p, uint8_t s, uint8_t d) {
  uint8_t r = 0;
  for (int i = 0; i < 8; ++i) {
    const int idx = ((p >> i) & 1) << 2 | ((s >> i) & 1) << 1 | ((d >> i) & 1);
    r |= uint8_t(((code >> idx) & 1) << i);
  }
  return r;
}

TEST(Rop3, AllCodesMatchTheTruthTable) {
  std::mt19937 rng(3);
  for (int code = 0; code < 256; ++code)
    for (int k = 0; k < 64; ++k) {
      const uint8_t p = uint8_t(rng()), s = uint8_t(rng()), d = uint8_t(rng());
      ASSERT_EQ(rop3(uint8_t(code), p, s, d), rop3_by_table(uint8_t(code), p, s, d))
          << "code " << code << " p " << int(p) << " s " << int(s) << " d " << int(d);
    }
}

TEST(Rop3, NamedCodesAreTheirFormulas) {
  std::mt19937 rng(4);
  for (int k = 0; k < 1000; ++k) {
    const uint8_t p = uint8_t(rng()), s = uint8_t(rng()), d = uint8_t(rng());
    EXPECT_EQ(rop3(kRopPatCopy, p, s, d), p);
    EXPECT_EQ(rop3(kRopSrcCopy, p, s, d), s);
    EXPECT_EQ(rop3(kRopPatInvert, p, s, d), uint8_t(p ^ d));
    EXPECT_EQ(rop3(kRopDstInvert, p, s, d), uint8_t(~d));
    EXPECT_EQ(rop3(kRopSrcInvert, p, s, d), uint8_t(s ^ d));
    EXPECT_EQ(rop3(kRopBlackness, p, s, d), 0);
    EXPECT_EQ(rop3(kRopWhiteness, p, s, d), 255);
    EXPECT_EQ(rop3(0x88, p, s, d), uint8_t(s & d));  // SRCAND
    EXPECT_EQ(rop3(0xEE, p, s, d), uint8_t(s | d));  // SRCPAINT
  }
}

TEST(Rop3, OperandUseByBruteForce) {
  int read_s = 0, read_d = 0;
  for (int code = 0; code < 256; ++code) {
    bool s_matters = false, d_matters = false;
    for (int p = 0; p < 2; ++p)
      for (int o = 0; o < 2; ++o) {
        s_matters |= rop3_by_table(uint8_t(code), p, 0, o) != rop3_by_table(uint8_t(code), p, 1, o);
        d_matters |= rop3_by_table(uint8_t(code), p, o, 0) != rop3_by_table(uint8_t(code), p, o, 1);
      }
    EXPECT_EQ(rop3_reads_source(uint8_t(code)), s_matters) << code;
    EXPECT_EQ(rop3_reads_destination(uint8_t(code)), d_matters) << code;
    read_s += s_matters;
    read_d += d_matters;
  }
  // Codes independent of an operand: 2^4 = 16 functions of the other two, so 240 read it.
  EXPECT_EQ(read_s, 240);
  EXPECT_EQ(read_d, 240);
}

}  // namespace
}  // namespace rastsim
