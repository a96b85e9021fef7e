// SPDX-License-Identifier: Apache-2.0
// The texture unit's failure points (docs/texture.md, "Failure points"; ctest -L texture):
// - the level of detail: log2_fixed8's chord under log2 first keeps a finer mip level
//   than exact log2 just above rho = sqrt(2) texels a pixel, and agrees again from
//   1 + 129/256;
// - the bilinear weights (texture.weight_bits): on one axis, 7 bits first change a
//   filtered colour by more than 1 LSB against the exact filter rounded; on two axes
//   truncated 8-bit weights already do (a hand-worked corner).
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
  TexelQuad q = texel_quad(s, 1 << (kF - 1), 2, 1, kF, true, TexWrap::Clamp, TexWrap::Clamp, bits);
  const Rgba8 a{uint8_t(t0), 0, 0, 255}, b{uint8_t(t1), 0, 0, 255};
  return filter_texels(q, {a, b, a, b})[0];
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

// Hand-worked: truncating x to b bits loses less than 2^-b, 255 2^-b before rounding:
// 0.996 at b = 8 (the rounded results differ by at most 1), 1.99 at b = 7 (x just below
// 1/128: exact 1.99 rounds to 2, golden 0).
TEST(TextureFailurePoints, WeightBitsOneAxisFirstFailAtSeven) {
  EXPECT_EQ(worst_1d(8), 1);
  EXPECT_EQ(worst_1d(7), 2);
  int first_fail = 0;
  for (int bits = 8; bits >= 1 && !first_fail; --bits)
    if (worst_1d(bits) > 1) first_fail = bits;
  EXPECT_EQ(first_fail, 7);
}

// Two axes, 8 bits: texels 0 (top-left) and 255 (the other three), alpha = beta just
// below 1/256 (u - 1/2 = 255/65536: s = (1/2 + 255/65536) 2^F / 2 of a 2 x 2 texture):
// exact 255 (1 - (1 - a)(1 - b)) = 1.98 rounds to 2; the truncated weights are 0: 0.
TEST(TextureFailurePoints, WeightBitsTwoAxesTruncationAtEight) {
  const int32_t s = int32_t(((int64_t{1} << 15) + 255) << (kF - 17));  // (1/2 + 255/65536) / 2 repeats
  const TexelQuad q = texel_quad(s, s, 2, 2, kF, true, TexWrap::Clamp, TexWrap::Clamp, 8);
  EXPECT_EQ(q.alpha, 0);
  EXPECT_EQ(q.beta, 0);
  const Rgba8 dark{0, 0, 0, 255}, light{255, 255, 255, 255};
  EXPECT_EQ(filter_texels(q, {dark, light, light, light})[0], 0);
  const double a = 255.0 / 65536;
  EXPECT_EQ(std::floor(255 * (1 - (1 - a) * (1 - a)) + 0.5), 2.0);  // the exact filter, rounded
}

// texture.weight_bits is honoured: x = 0.3 of the way from 0 to 255 (s = 0.4 repeats of a
// 2-texel axis: u - 1/2 = 0.3), 8 bits: alpha = floor(0.3 256) = 76, (255 76 + 128) >> 8
// = 76; 4 bits: alpha = 64 (76 with its low 4 of 8 bits cleared), 255 64 / 256 = 63.75: 64.
TEST(TextureFailurePoints, WeightBitsHonouredBySampler) {
  const int32_t s = int32_t(std::llround(0.4 * (1 << kF)));
  EXPECT_EQ(golden_1d(0, 255, s, 8), 76);
  EXPECT_EQ(golden_1d(0, 255, s, 4), 64);
}

}  // namespace
}  // namespace rastsim
