// SPDX-License-Identifier: Apache-2.0
// The texture unit's failure points (docs/texture.md, "Failure points"; ctest -L texture):
// - the level of detail: log2_fixed8's chord under log2 first keeps a finer mip level
//   than exact log2 just above rho = sqrt(2) texels a pixel, and agrees again from
//   1 + 129/256;
// - the bilinear weights (texture.weight_bits, x = u - 1/2 rounded to nearest at B bits):
//   against the exact filter rounded, one axis first misses by more than 1 LSB at 6 bits,
//   two axes at 7 (brute force, and a hand-worked corner).
#include <gtest/gtest.h>

#include <cmath>

#include "ref/texture/texture_unit.h"

namespace rastsim {
namespace {

constexpr int kF = 20;  // interp.texcoord_format s7.20, the default

// The mip level exact log2 picks for rho (raw 2^-F texels): the nearest level, ties to
// the finer: ceil(log2(rho) - 1/2), at least 0.
int exact_level(uint64_t rho) {
  const double lambda = std::log2(double(rho)) - kF;
  return std::max(0, int(std::ceil(lambda - 0.5)));
}

int golden_level(uint64_t rho) {
  return choose_levels(log2_fixed8(rho) - kF * 256, 0, 8, TexFilter::Nearest).level0;
}

// Hand-worked: exact log2 moves to level 1 above rho = sqrt(2) = 1.41421356 texels, the
// first raw value floor(sqrt(2) 2^20) + 1 = 1482911; log2_fixed8 gives n = 20 and the
// fraction floor((rho - 2^20) / 2^12), level 1 from fraction 129 ((129 + 127) >> 8 = 1):
// rho >= 2^20 + 129 2^12 = 1576960 (1.50390625 texels). Brute force over [1, 2) texels (every
// octave has its band: [2 sqrt(2), 2 1.50390625) the next).
TEST(TextureFailurePoints, LodApproximationFirstDiffersAboveRootTwo) {
  uint64_t first = 0, last = 0, count = 0;
  for (uint64_t rho = uint64_t{1} << kF; rho < uint64_t{2} << kF; ++rho)
    if (golden_level(rho) != exact_level(rho)) {
      if (!first) first = rho;
      last = rho;
      ++count;
    }
  EXPECT_EQ(first, 1482911u);
  EXPECT_EQ(last, 1576959u);
  EXPECT_EQ(count, 1576960u - 1482911u);  // one band
}

// The bilinear colour of texels t0 (left) and t1 at weight position x in [0, 1) of an
// axis, golden with `bits` weight bits: a 2 x 1 texture, clamp, t on the row's centre.
int golden_1d(int t0, int t1, int32_t s, int bits) {
  const TexelQuad q = texel_quad(s, 1 << (kF - 1), 2, 1, kF, true, TexWrap::Clamp, TexWrap::Clamp, bits);
  std::array<Rgba8, 4> t{};
  for (size_t n = 0; n < 4; ++n) t[n] = {uint8_t(q.i[n] ? t1 : t0), 0, 0, 255};  // the texels the quad names
  return filter_texels(q, t)[0];
}

// One axis: s from texel 0's centre (2^F / 4) to texel 1's, every raw step; the worst
// pair 0 and 255. Exact: t0 + (t1 - t0) x, x = 2 s / 2^F - 1/2, rounded to nearest.
int worst_1d(int bits) {
  int worst = 0;
  for (int32_t s = 1 << (kF - 2); s < 3 << (kF - 2); ++s) {
    const double x = 2.0 * s / double(1 << kF) - 0.5;
    worst = std::max(worst, std::abs(golden_1d(0, 255, s, bits) - int(std::floor(255 * x + 0.5))));
  }
  return worst;
}

// Hand-worked: rounding x to b bits moves it by at most 2^-(b+1), 255 2^-(b+1) of a
// channel before the final rounding: 0.498 at b = 8 and 0.996 at b = 7 (below 1, so the
// rounded results differ by at most 1), 1.99 at b = 6 (x just below the tie 1/128: exact
// 1.99 rounds to 2, x rounds to 0: golden 0).
TEST(TextureFailurePoints, WeightBitsOneAxisFirstFailAtSix) {
  EXPECT_EQ(worst_1d(8), 1);
  EXPECT_EQ(worst_1d(7), 1);
  EXPECT_EQ(worst_1d(6), 2);
  int first_fail = 0;
  for (int bits = 8; bits >= 1 && !first_fail; --bits)
    if (worst_1d(bits) > 1) first_fail = bits;
  EXPECT_EQ(first_fail, 6);
}

// u - 1/2 = x on both axes of a 2 x 2 texture: s = (x + 1/2) 2^F / 2.
int32_t two_by_two_coord(double x) { return int32_t(std::llround((x + 0.5) * (1 << (kF - 1)))); }

// Two axes: the worst |golden - exact rounded| of channel 0 over the 16 textures of
// texels 0 and 255 and x, y in [0, 1/16) texel every 2^-11 (exact in raw units; x's
// rounding error repeats every 2^-b texel, so the square holds every case for b >= 4).
int worst_2d(int bits) {
  int worst = 0;
  for (int k = 0; k < 128; ++k)
    for (int m = 0; m < 128; ++m) {
      const double x = k / 2048.0, y = m / 2048.0;
      const TexelQuad q = texel_quad(two_by_two_coord(x), two_by_two_coord(y), 2, 2, kF, true, TexWrap::Clamp,
                                     TexWrap::Clamp, bits);
      for (int pattern = 0; pattern < 16; ++pattern) {  // bit 2 j + i: texel (i, j) is 255
        const auto texel = [&](int i, int j) { return (pattern >> (2 * j + i)) & 1 ? 255 : 0; };
        std::array<Rgba8, 4> t{};
        for (size_t n = 0; n < 4; ++n) t[n] = {uint8_t(texel(q.i[n], q.j[n])), 0, 0, 255};
        const double exact = texel(0, 0) * (1 - x) * (1 - y) + texel(1, 0) * x * (1 - y) +
                             texel(0, 1) * (1 - x) * y + texel(1, 1) * x * y;
        worst = std::max(worst, std::abs(filter_texels(q, t)[0] - int(std::floor(exact + 0.5))));
      }
    }
  return worst;
}

// Hand-worked: two axes add their losses, 255 (2^-(b+1) + 2^-(b+1)) = 0.996 at b = 8
// (within 1 LSB), 1.99 at b = 7. Brute force finds 7 the first width beyond 1 LSB.
TEST(TextureFailurePoints, WeightBitsTwoAxesFirstFailAtSeven) {
  EXPECT_EQ(worst_2d(8), 1);
  int first_fail = 0;
  for (int bits = 8; bits >= 4 && !first_fail; --bits)
    if (worst_2d(bits) > 1) first_fail = bits;
  EXPECT_EQ(first_fail, 7);
}

// Two axes by hand: texels 0 (top-left) and 255 (the other three), x = y = 255/65536,
// just below 1/256 (s = (1/2 + 255/65536) 2^F / 2 of a 2 x 2 texture). Exact
// 255 (1 - (1 - x)^2) = 1.98 rounds to 2. 8 bits: x 256 = 0.996 rounds to 1, alpha = beta
// = 1: (255 (255 + 255 + 1) + 2^15) >> 16 = 163073 >> 16 = 2, exact. 7 bits: x 128 = 0.498
// rounds to 0, alpha = beta = 0: 0, 2 LSB off.
TEST(TextureFailurePoints, WeightBitsTwoAxesCornerHandWorked) {
  const int32_t s = int32_t(((int64_t{1} << 15) + 255) << (kF - 17));  // (1/2 + 255/65536) / 2 repeats
  const Rgba8 dark{0, 0, 0, 255}, light{255, 255, 255, 255};
  const TexelQuad q8 = texel_quad(s, s, 2, 2, kF, true, TexWrap::Clamp, TexWrap::Clamp, 8);
  EXPECT_EQ(q8.alpha, 1);
  EXPECT_EQ(q8.beta, 1);
  EXPECT_EQ(filter_texels(q8, {dark, light, light, light})[0], 2);
  const TexelQuad q7 = texel_quad(s, s, 2, 2, kF, true, TexWrap::Clamp, TexWrap::Clamp, 7);
  EXPECT_EQ(q7.alpha, 0);
  EXPECT_EQ(filter_texels(q7, {dark, light, light, light})[0], 0);
  const double x = 255.0 / 65536;
  EXPECT_EQ(std::floor(255 * (1 - (1 - x) * (1 - x)) + 0.5), 2.0);  // the exact filter, rounded
}

// texture.weight_bits is honoured: x about 0.3 of the way from 0 to 255 (s = round(0.4 2^F)
// = 419430 of a 2-texel axis: x = 2 419430 / 2^20 - 1/2 = 0.29999924). 8 bits: x 256 =
// 76.79998 rounds to alpha 77, (255 77 + 128) >> 8 = 77 (exact 76.4998: 76, 1 LSB);
// 4 bits: x 16 = 4.79999 rounds to 5, alpha 80, 255 80 / 256 = 79.69: 80.
TEST(TextureFailurePoints, WeightBitsHonouredBySampler) {
  const int32_t s = int32_t(std::llround(0.4 * (1 << kF)));
  EXPECT_EQ(golden_1d(0, 255, s, 8), 77);
  EXPECT_EQ(golden_1d(0, 255, s, 4), 80);
}

}  // namespace
}  // namespace rastsim
