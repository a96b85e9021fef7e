// SPDX-License-Identifier: Apache-2.0
// rast_line against the reference index methods (model/ref/2d/line_raster.h), pixel by pixel,
// with random stalls on the output; counts cycles and checks the cycle equation
// cycles = 1 (set-up) + max(|dX|, |dY|) + 1 pixels + stall cycles.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "Vrast_line.h"
#include "ref/2d/line_raster.h"

namespace {

constexpr int kWidth = 16;  // rast_line's Width (default parameter)

struct LineBench {
  Vrast_line dut;
  uint64_t cycles = 0;
  LineBench() {
    dut.clk_i = 0;
    dut.rst_ni = 0;
    dut.in_valid_i = 0;
    dut.out_ready_i = 0;
    dut.eval();
    dut.rst_ni = 1;
    dut.eval();
  }
  void tick() {
    dut.clk_i = 1;
    dut.eval();
    dut.clk_i = 0;
    dut.eval();
    ++cycles;
  }
  static uint16_t enc(int v) { return uint16_t(v) & ((1u << kWidth) - 1); }
  static int dec(int v) { return int(int16_t(uint16_t(v))); }
  // Draws one line; returns its pixels, counts stall-free cycles in `busy`.
  std::vector<std::pair<int, int>> draw(int x0, int y0, int x1, int y1, bool midpoint,
                                        std::mt19937& rng, int stall_pct, uint64_t& stalls) {
    std::vector<std::pair<int, int>> px;
    dut.x0_i = enc(x0);
    dut.y0_i = enc(y0);
    dut.x1_i = enc(x1);
    dut.y1_i = enc(y1);
    dut.midpoint_i = midpoint;
    dut.in_valid_i = 1;
    dut.out_ready_i = 0;
    dut.eval();
    EXPECT_TRUE(dut.in_ready_o);
    tick();
    dut.in_valid_i = 0;
    for (int guard = 0; guard < 1 << 20; ++guard) {
      const bool ready = int(rng() % 100) >= stall_pct;
      dut.out_ready_i = ready;
      dut.eval();
      if (!dut.out_valid_o) {
        ADD_FAILURE() << "no pixel";
        return px;
      }
      const bool last = dut.out_last_o;
      if (ready) px.emplace_back(dec(dut.out_x_o), dec(dut.out_y_o));
      else ++stalls;
      tick();
      if (ready && last) return px;
    }
    ADD_FAILURE() << "line never ended";
    return px;
  }
};

std::vector<std::pair<int, int>> reference(int x0, int y0, int x1, int y1, bool midpoint) {
  std::vector<std::pair<int, int>> px;
  auto emit = [&](int x, int y) { px.emplace_back(x, y); };
  if (midpoint) rastsim::midpoint_line(x0, y0, x1, y1, emit);
  else rastsim::bresenham_line(x0, y0, x1, y1, emit);
  return px;
}

void run_random(bool midpoint, uint32_t seed, int count, int range) {
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> c(-range, range);
  LineBench tb;
  uint64_t pixels = 0, stalls = 0;
  int octant_seen[16] = {};
  for (int n = 0; n < count; ++n) {
    int x0 = c(rng), y0 = c(rng), x1 = c(rng), y1 = c(rng);
    if (n % 4 == 0) {  // exact diagonals, axis lines and 2:1 slopes make ties
      const int k = int(rng() % 40) - 20, kind = int(rng() % 4);
      x1 = x0 + (kind == 0 ? k : 2 * k);
      y1 = y0 + (kind == 1 ? 0 : kind == 2 ? k : (rng() & 1 ? k : -k));
    }
    const uint64_t before = tb.cycles, stalls_before = stalls;
    const auto got = tb.draw(x0, y0, x1, y1, midpoint, rng, 20, stalls);
    const auto want = reference(x0, y0, x1, y1, midpoint);
    SCOPED_TRACE(::testing::Message() << "line " << x0 << "," << y0 << " -> " << x1 << "," << y1);
    ASSERT_EQ(got, want);
    const uint64_t a = uint64_t(std::max(std::abs(x1 - x0), std::abs(y1 - y0)));
    ASSERT_EQ(tb.cycles - before, 1 + (a + 1) + (stalls - stalls_before));
    pixels += got.size();
    octant_seen[(x1 > x0) | (y1 > y0) << 1 | (std::abs(y1 - y0) > std::abs(x1 - x0)) << 2] = 1;
  }
  for (int o = 0; o < 8; ++o) EXPECT_TRUE(octant_seen[o]) << "octant " << o;
  std::printf("%d lines, %llu pixels, %llu cycles (%llu stall)\n", count, (unsigned long long)pixels,
              (unsigned long long)tb.cycles, (unsigned long long)stalls);
}

TEST(RtlLine, BresenhamRandomAllOctants) { run_random(false, 0x2d11e, 4000, 200); }
TEST(RtlLine, MidpointRandomAllOctants) { run_random(true, 0x2d11f, 4000, 200); }
TEST(RtlLine, FullWidthExtremes) {
  std::mt19937 rng(7);
  LineBench tb;
  uint64_t stalls = 0;
  const int lo = -(1 << (kWidth - 1)), hi = (1 << (kWidth - 1)) - 1;
  for (bool mid : {false, true}) {
    for (auto [x0, y0, x1, y1] : {std::tuple{lo, lo, hi, hi}, {hi, lo, lo, hi}, {lo, 0, hi, 1}, {0, hi, 3, lo},
                                  {5, 5, 5, 5}}) {
      ASSERT_EQ(tb.draw(x0, y0, x1, y1, mid, rng, 0, stalls), reference(x0, y0, x1, y1, mid));
    }
  }
}

}  // namespace
