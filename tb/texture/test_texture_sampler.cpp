// SPDX-License-Identifier: Apache-2.0
// The golden sampler (ref/texture) against the independent one (independent_sampler.h) on
// random textures, coordinates, derivatives, wraps, formats, filters and biases, exact
// texel-boundary ties included; and hand-worked cases (ctest -L texture).
#include <gtest/gtest.h>

#include <random>

#include "independent_sampler.h"
#include "ref/texture/texture_unit.h"

namespace rastsim {
namespace {

using texture_test::RefQuery;

constexpr int kF = 20;  // interp.texcoord_format s7.20, the default

std::shared_ptr<const TextureImage> image(int w, int h, const std::vector<uint8_t>& rgba) {
  auto t = std::make_shared<TextureImage>();
  t->name = "hand";
  t->width = w;
  t->height = h;
  t->rgba = rgba;
  return t;
}

// The golden colour of one sample (no cache: the counts do not matter here).
std::array<int, 3> golden(const TextureState& ts, TexelFormat format, const RefQuery& q) {
  TextureParams p;
  p.format = format;
  p.weight_bits = q.weight_bits;
  TextureUnit unit(p);
  Fragment f;
  f.s = q.s;
  f.t = q.t;
  f.r = uint8_t(q.color[0]);
  f.g = uint8_t(q.color[1]);
  f.b = uint8_t(q.color[2]);
  const Fragment out = unit.shade(f, {q.dsdx, q.dtdx, q.dsdy, q.dtdy}, ts, q.frac_bits);
  return {out.r, out.g, out.b};
}

std::array<int, 3> independent(const TextureState& ts, TexelFormat format, const RefQuery& q) {
  const auto c = texture_test::ref_sample(texture_test::ref_chain(*ts.image, format), q, ts);
  return {int(c[0]), int(c[1]), int(c[2])};
}

// A coordinate on an n-texel axis: often exactly on a texel edge k / n or centre
// (k + 1/2) / n, or on a bilinear weight tie u = (2k + 1) / 512 (u - 1/2 halfway between
// two 1/256 steps) (each exact where n divides 2^F), else anywhere in a few repeats
// either side.
int32_t random_coord(std::mt19937_64& rng, int n) {
  const int kind = int(rng() % 5);
  const int64_t k = int64_t(rng() % uint64_t(6 * n)) - 3 * n;
  if (kind == 0) return int32_t((k << kF) / n);                      // an edge (exact when n divides 2^F)
  if (kind == 1) return int32_t(((2 * k + 1) << (kF - 1)) / n);      // a centre
  if (kind == 2) return int32_t(((2 * (k * 256 + int64_t(rng() % 256)) + 1) << (kF - 9)) / n);  // a weight tie
  return int32_t(int64_t(rng() % (uint64_t(6) << kF)) - (int64_t{3} << kF));
}

int64_t random_derivative(std::mt19937_64& rng) {
  switch (rng() % 4) {
    case 0: return 0;
    case 1: return int64_t(rng() % (uint64_t(1) << kF)) - (int64_t{1} << (kF - 1));  // under a repeat a pixel
    case 2: return int64_t{1} << (kF - int(rng() % 8));                               // exact powers of two
    default: return int64_t(rng() % 4096) - 2048;                                     // magnification
  }
}

TEST(TextureSampler, GoldenEqualsIndependentOnRandomSamples) {
  std::mt19937_64 rng(28);
  const int sides[] = {1, 2, 3, 4, 5, 8, 16, 7, 32};
  int compared = 0;
  for (int tex = 0; tex < 120; ++tex) {
    const int w = sides[rng() % 9], h = sides[rng() % 9];
    std::vector<uint8_t> rgba(size_t(w * h * 4));
    for (uint8_t& c : rgba) c = uint8_t(rng());
    TextureState ts;
    ts.image = image(w, h, rgba);
    const TexelFormat format = TexelFormat(rng() % 3);
    for (int k = 0; k < 100; ++k) {
      ts.filter = TexFilter(rng() % 3);
      ts.wrap_s = TexWrap(rng() % 3);
      ts.wrap_t = TexWrap(rng() % 3);
      ts.env = TexEnv(rng() % 3);
      ts.mipmap = rng() % 4 != 0;
      ts.lod_bias = int32_t(rng() % 1025) - 512;
      RefQuery q;
      q.frac_bits = kF;
      q.weight_bits = rng() % 2 ? kMaxWeightBits : 1 + int(rng() % kMaxWeightBits);
      q.s = random_coord(rng, w);
      q.t = random_coord(rng, h);
      q.dsdx = random_derivative(rng), q.dtdx = random_derivative(rng);
      q.dsdy = random_derivative(rng), q.dtdy = random_derivative(rng);
      q.color = {double(rng() % 256), double(rng() % 256), double(rng() % 256)};
      ASSERT_EQ(golden(ts, format, q), independent(ts, format, q))
          << w << "x" << h << " format " << int(format) << " filter " << to_string(ts.filter) << " wrap "
          << int(ts.wrap_s) << int(ts.wrap_t) << " env " << int(ts.env) << " mipmap " << ts.mipmap << " bias "
          << ts.lod_bias << " s " << q.s << " t " << q.t << " d " << q.dsdx << " " << q.dtdx << " " << q.dsdy << " "
          << q.dtdy;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 12000);
}

// A 2x2 texture, texels A B / C D (row 0 = t in [0, 1/2), the file's top row).
const std::vector<uint8_t> kTwoByTwo = {10, 20, 30, 255,  50, 60, 70, 255,  // A B
                                        90, 100, 110, 255, 132, 140, 150, 255};  // C D

Fragment at(double s, double t) {
  Fragment f;
  f.s = int32_t(s * (1 << kF));
  f.t = int32_t(t * (1 << kF));
  f.r = f.g = f.b = 255;
  return f;
}

std::array<int, 3> rgb(const Fragment& f) { return {f.r, f.g, f.b}; }

TEST(TextureSampler, NearestAtCentresAndEdgesOfATwoByTwo) {
  TextureUnit unit(TextureParams{});
  TextureState ts;
  ts.image = image(2, 2, kTwoByTwo);
  ts.filter = TexFilter::Nearest;
  ts.env = TexEnv::Replace;
  const QuadDerivatives d{};
  EXPECT_EQ(rgb(unit.shade(at(0.25, 0.25), d, ts, kF)), (std::array<int, 3>{10, 20, 30}));    // A's centre
  EXPECT_EQ(rgb(unit.shade(at(0.75, 0.25), d, ts, kF)), (std::array<int, 3>{50, 60, 70}));    // B's centre
  EXPECT_EQ(rgb(unit.shade(at(0.25, 0.75), d, ts, kF)), (std::array<int, 3>{90, 100, 110}));  // C: t down
  // The edge s = 1/2 belongs to the texel right of it ([i, i + 1) / W), t = 1/2 to the row below.
  EXPECT_EQ(rgb(unit.shade(at(0.5, 0.5), d, ts, kF)), (std::array<int, 3>{132, 140, 150}));
  EXPECT_EQ(rgb(unit.shade(at(0.0, 0.0), d, ts, kF)), (std::array<int, 3>{10, 20, 30}));
  // s = 1: repeat wraps to texel 0, clamp keeps texel 1, mirror reflects to texel 1.
  EXPECT_EQ(rgb(unit.shade(at(1.0, 0.25), d, ts, kF)), (std::array<int, 3>{10, 20, 30}));
  ts.wrap_s = TexWrap::Clamp;
  EXPECT_EQ(rgb(unit.shade(at(1.0, 0.25), d, ts, kF)), (std::array<int, 3>{50, 60, 70}));
  ts.wrap_s = TexWrap::Mirror;
  EXPECT_EQ(rgb(unit.shade(at(1.0, 0.25), d, ts, kF)), (std::array<int, 3>{50, 60, 70}));
  EXPECT_EQ(rgb(unit.shade(at(1.75, 0.25), d, ts, kF)), (std::array<int, 3>{10, 20, 30}));  // mirrored: texel 0
}

TEST(TextureSampler, BilinearAtTheMidpointAndAtACentre) {
  TextureUnit unit(TextureParams{});
  TextureState ts;
  ts.image = image(2, 2, kTwoByTwo);
  ts.env = TexEnv::Replace;
  const QuadDerivatives d{};
  // (1/2, 1/2): u - 1/2 = 1/2 on both axes, weights 128/256 each: the mean of A B C D.
  // Red (10 + 50 + 90 + 132) / 4 = 70.5 -> 71 (ties up); green 320 / 4 = 80; blue 360 / 4 = 90.
  EXPECT_EQ(rgb(unit.shade(at(0.5, 0.5), d, ts, kF)), (std::array<int, 3>{71, 80, 90}));
  // A texel's centre: weight 0 on the others, the texel itself.
  EXPECT_EQ(rgb(unit.shade(at(0.25, 0.25), d, ts, kF)), (std::array<int, 3>{10, 20, 30}));
  // (3/8, 1/4): u - 1/2 = 1/4, weight 64 of B: red (10 192 + 50 64) / 256 = 20.
  EXPECT_EQ(rgb(unit.shade(at(0.375, 0.25), d, ts, kF)), (std::array<int, 3>{20, 30, 40}));
}

// The weight is u - 1/2 rounded to the nearest 1/256 texel, ties up. On a 2-texel axis
// u = 2 s, so s = 3/8 + 1/1024 (raw 393216 + 1024 = 394240) puts u - 1/2 at 1/4 + 1/512,
// the tie 64.5/256: weight 65; one raw step lower (64.5 - 2^-11) rounds to 64. s = 3/4 -
// 1/2048 (raw 786432 - 512 = 785920): u - 1/2 = 1 - 1/1024, 255.75/256, rounds to the whole
// texel 1: i0 = 1 (i1 = 2 wraps to 0), weight 0.
TEST(TextureSampler, BilinearWeightRoundsToNearestTiesUp) {
  const int32_t t = 1 << (kF - 2);  // row 0's centre: v - 1/2 = 0
  const auto quad = [&](int32_t s) { return texel_quad(s, t, 2, 2, kF, true, TexWrap::Repeat, TexWrap::Repeat); };
  EXPECT_EQ(quad(394240).alpha, 65);
  EXPECT_EQ(quad(394239).alpha, 64);
  EXPECT_EQ(quad(394240).i[0], 0);
  const TexelQuad whole = quad(785920);
  EXPECT_EQ(whole.alpha, 0);
  EXPECT_EQ(whole.i[0], 1);
  EXPECT_EQ(whole.i[1], 0);
  EXPECT_EQ(whole.beta, 0);
  // Negative coordinates round the same way (up at a tie): s = -1/8 + 1/1024 (raw -131072
  // + 1024): u - 1/2 = -3/4 + 1/512 = -1 + 64.5/256: i0 = -1 (wraps to 1), weight 65.
  const TexelQuad neg = quad(-131072 + 1024);
  EXPECT_EQ(neg.i[0], 1);
  EXPECT_EQ(neg.alpha, 65);
}

TEST(TextureSampler, LevelOfDetailHandWorked) {
  // rho = 4 texels a pixel: lambda 2 exactly.
  EXPECT_EQ(texture_lod({1 << (kF - 2), 0, 0, 1 << (kF - 2)}, 16, 16, kF), 2 * 256);
  // rho = 3: n = 1, the next 8 bits 1000 0000: lambda 1.5 (exact log2 3 = 1.585).
  EXPECT_EQ(texture_lod({3 << (kF - 4), 0, 0, 0}, 16, 16, kF), 384);
  // Length of (3, 4): 4 + 3/2 = 5.5 (exact 5); rho = 5.5 -> n = 2, 5.5/4 = 1.375: lambda 2.375.
  EXPECT_EQ(texture_lod({3 << (kF - 4), 4 << (kF - 4), 0, 0}, 16, 16, kF), 2 * 256 + 96);
  EXPECT_EQ(texture_lod({}, 16, 16, kF), kLodMinusInfinity);
  // Nearest level: 1.5 is a tie, to the finer level 1; 1.5 + 1/256 goes to 2.
  EXPECT_EQ(choose_levels(384, 0, 5, TexFilter::Nearest).level0, 1);
  EXPECT_EQ(choose_levels(385, 0, 5, TexFilter::Bilinear).level0, 2);
  // Trilinear 1.5: levels 1 and 2 at weight 128; bias -2 clamps to level 0 alone.
  const LevelChoice c = choose_levels(384, 0, 5, TexFilter::Trilinear);
  EXPECT_EQ(c.level0, 1);
  EXPECT_EQ(c.level1, 2);
  EXPECT_EQ(c.frac, 128);
  EXPECT_EQ(choose_levels(384, -512, 5, TexFilter::Trilinear).level1, 0);
  EXPECT_EQ(choose_levels(9 * 256, 0, 5, TexFilter::Trilinear).level0, 4);  // clamped to the last level
}

TEST(TextureSampler, MipChainBoxFilterAndFormatsHandWorked) {
  const auto chain = build_mip_chain(*image(2, 2, kTwoByTwo), TexelFormat::Rgba8888, true);
  ASSERT_EQ(chain.size(), 2u);
  EXPECT_EQ(chain[1].texel(0, 0), (Rgba8{71, 80, 90, 255}));  // (282 + 2) >> 2 = 71, as bilinear's tie
  // RGB565: 200 -> round(200 31 / 255) = 24 -> 24 << 3 | 24 >> 2 = 198; green round(200 63 / 255)
  // = 49 -> 49 << 2 | 49 >> 4 = 199. L8: (77 200 + 150 100 + 29 50 + 128) >> 8 = 31978 >> 8 = 124.
  EXPECT_EQ(to_texel_format({200, 200, 200, 7}, TexelFormat::Rgb565), (Rgba8{198, 199, 198, 255}));
  EXPECT_EQ(to_texel_format({200, 100, 50, 7}, TexelFormat::L8), (Rgba8{124, 124, 124, 255}));
  EXPECT_EQ(to_texel_format({255, 255, 255, 255}, TexelFormat::L8), (Rgba8{255, 255, 255, 255}));
}

TEST(TextureSampler, TexenvRoundingHandWorked) {
  // modulate: 100 100 / 255 = 39.2 -> 39; 128 255 / 255 = 128. decal with alpha 128 over
  // colour 0: 255 128 / 255 = 128. replace: the texel.
  EXPECT_EQ(texenv_combine(TexEnv::Modulate, {100, 128, 0, 255}, {100, 255, 9}), (std::array<uint8_t, 3>{39, 128, 0}));
  EXPECT_EQ(texenv_combine(TexEnv::Decal, {255, 0, 10, 128}, {0, 200, 10}), (std::array<uint8_t, 3>{128, 100, 10}));
  EXPECT_EQ(texenv_combine(TexEnv::Replace, {1, 2, 3, 0}, {9, 9, 9}), (std::array<uint8_t, 3>{1, 2, 3}));
}

TEST(TextureSampler, CacheCountsFetchesHitsMissesAndBytes) {
  TextureParams p;
  p.cache = {1024, 2, 64};  // 8 sets of 2 ways
  TextureUnit unit(p);
  TextureState ts;
  ts.image = image(2, 2, kTwoByTwo);
  const QuadDerivatives d{};
  unit.shade(at(0.5, 0.5), d, ts, kF);  // bilinear: 4 fetches of one 16-byte texture: 1 miss, 3 hits
  unit.shade(at(0.25, 0.25), d, ts, kF);
  const TextureStats& s = unit.stats();
  EXPECT_EQ(s.texel_fetches, 8u);
  EXPECT_EQ(s.cache_misses, 1u);
  EXPECT_EQ(s.cache_hits, 7u);
  EXPECT_EQ(s.dram_bytes, 64u);
  EXPECT_EQ(s.samples[size_t(TexFilter::Bilinear)], 2u);
  // No cache: every fetch reads its own texel (4 bytes of RGBA8888).
  TextureUnit bare(TextureParams{});
  bare.shade(at(0.5, 0.5), d, ts, kF);
  EXPECT_EQ(bare.stats().cache_misses, 4u);
  EXPECT_EQ(bare.stats().dram_bytes, 16u);
}

TEST(TextureSampler, LayoutsPlaceTexelsAsStated) {
  // 8 x 8 texels of 4 bytes. Linear: row-major. Tiled: 4 x 4 tiles, tile 1 (x 4..7, y 0..3)
  // starts at 16 texels. Morton: x bits even, y bits odd: (3, 5) -> x 011, y 101 -> 100111 = 39.
  EXPECT_EQ(texel_offset(TexLayout::Linear, 8, 8, 4, 3, 5), (5u * 8 + 3) * 4);
  EXPECT_EQ(texel_offset(TexLayout::Tiled, 8, 8, 4, 5, 1), (16u + 1 * 4 + 1) * 4);
  EXPECT_EQ(texel_offset(TexLayout::Morton, 8, 8, 4, 3, 5), 39u * 4);
  EXPECT_EQ(level_footprint(TexLayout::Morton, 8, 3, 1), 64u);  // padded to 8 x 8
  EXPECT_EQ(level_footprint(TexLayout::Tiled, 5, 5, 2), 64u * 2);  // 2 x 2 tiles of 16 texels
}

}  // namespace
}  // namespace rastsim
