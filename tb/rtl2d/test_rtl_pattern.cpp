// SPDX-License-Identifier: Apache-2.0
// rast_pattern against the `pattern HEX16` text: row r is hex digits 2r, 2r+1, MSB leftmost.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "Vrast_pattern.h"

namespace {

TEST(RtlPattern, RandomPatternsScreenAnchored) {
  const uint32_t seed = 0x8a77;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  Vrast_pattern dut;
  const char* hex = "0123456789ABCDEF";
  for (int n = 0; n < 200; ++n) {
    std::string text;
    for (int i = 0; i < 16; ++i) text += hex[rng() % 16];
    const uint32_t fg = uint32_t(rng()) & 0xffffff, bg = uint32_t(rng()) & 0xffffff;
    dut.pattern_i = std::stoull(text, nullptr, 16);
    dut.fg_i = fg;
    dut.bg_i = bg;
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 24; ++x) {
        const int row = y % 8, col = x % 8;
        const int row_bits = std::stoi(text.substr(size_t(2 * row), 2), nullptr, 16);
        const bool on = (row_bits >> (7 - col)) & 1;
        dut.x_i = uint8_t(x & 7);
        dut.y_i = uint8_t(y & 7);
        dut.eval();
        ASSERT_EQ(dut.p_o, on ? fg : bg) << text << " at " << x << "," << y;
      }
    }
  }
}

}  // namespace
