// SPDX-License-Identifier: Apache-2.0
// The filter-error study (docs/results.md, "Texture filtering: error and cache"; run by
// scripts/texture_study, not by ctest: DISABLED_): the golden sampler's nearest, bilinear
// and trilinear, and bilinear at every texture.weight_bits, against an exact
// double-precision filter of the same mip chain (Euclidean lengths, exact log2, exact
// weights and blend, nothing rounded), over random coordinates and derivatives on a
// 64 x 64 procedural texture. Prints markdown table rows: mean and max |error| per
// channel (R, G, B, in 8-bit LSBs) and PSNR (dB, over the three channels).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "independent_sampler.h"
#include "ref/texture/texture_unit.h"

namespace rastsim {
namespace {

using texture_test::RefImage;
using texture_test::ref_wrap;

constexpr int kF = 20;  // interp.texcoord_format s7.20
constexpr int kSide = 64;
constexpr int kSamples = 40000;

// Smooth waves of three periods plus +-24 of noise per channel: edges and gradients both.
std::shared_ptr<const TextureImage> study_texture() {
  auto t = std::make_shared<TextureImage>();
  t->name = "study";
  t->width = t->height = kSide;
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> noise(-24, 24);
  const double pi = std::acos(-1.0);
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      for (int ch = 0; ch < 3; ++ch) {
        const double p = 8.0 + 5.0 * ch;
        const double v = 128 + 90 * std::sin(2 * pi * i / p) * std::cos(2 * pi * j / (p + 3)) + noise(rng);
        t->rgba.push_back(uint8_t(std::clamp(v, 0.0, 255.0)));
        if (ch == 2) t->rgba.push_back(255);
      }
  return t;
}

struct Query {
  int32_t s = 0, t = 0;
  QuadDerivatives d;
};

// One level's exact filtered colour: nearest the texel holding (u, v); bilinear the four
// around (u - 1/2, v - 1/2) with exact weights.
std::array<double, 3> exact_level(const RefImage& l, const Query& q, bool bilinear) {
  const double u = std::ldexp(double(q.s), -kF) * l.w, v = std::ldexp(double(q.t), -kF) * l.h;
  std::array<double, 3> out{};
  if (!bilinear) {
    const auto& c = l.at(ref_wrap(std::floor(u), l.w, TexWrap::Repeat), ref_wrap(std::floor(v), l.h, TexWrap::Repeat));
    return {c[0], c[1], c[2]};
  }
  const double i0 = std::floor(u - 0.5), j0 = std::floor(v - 0.5), a = u - 0.5 - i0, b = v - 0.5 - j0;
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const auto& c = l.at(ref_wrap(i0 + di, l.w, TexWrap::Repeat), ref_wrap(j0 + dj, l.h, TexWrap::Repeat));
      for (size_t ch = 0; ch < 3; ++ch) out[ch] += (di ? a : 1 - a) * (dj ? b : 1 - b) * c[ch];
    }
  return out;
}

// The exact level of detail: log2 of the longer Euclidean derivative length in texels.
double exact_lambda(const Query& q) {
  const auto len = [&](int64_t ds, int64_t dt) {
    return std::hypot(std::ldexp(double(ds), -kF) * kSide, std::ldexp(double(dt), -kF) * kSide);
  };
  const double rho = std::max(len(q.d.dsdx, q.d.dtdx), len(q.d.dsdy, q.d.dtdy));
  return rho > 0 ? std::log2(rho) : -1e9;
}

// The exact sample at the exact level of detail.
std::array<double, 3> exact_sample(const std::vector<RefImage>& chain, const Query& q, TexFilter f) {
  const double top = double(chain.size() - 1);
  const double l = std::clamp(exact_lambda(q), 0.0, top);
  if (f != TexFilter::Trilinear) return exact_level(chain[size_t(std::max(0.0, std::ceil(l - 0.5)))], q, f == TexFilter::Bilinear);
  const double k = std::floor(l), frac = l - k;
  const auto c0 = exact_level(chain[size_t(k)], q, true), c1 = exact_level(chain[size_t(std::min(k + 1, top))], q, true);
  return {c0[0] * (1 - frac) + c1[0] * frac, c0[1] * (1 - frac) + c1[1] * frac, c0[2] * (1 - frac) + c1[2] * frac};
}

// Random points in [0, 2) repeats; rho log-uniform in [1/4, 32] texels a pixel, a random
// direction, the y derivative at right angles, 1 to 2 times shorter.
std::vector<Query> study_queries() {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double pi = std::acos(-1.0), one = std::ldexp(1.0, kF);
  std::vector<Query> out;
  for (int n = 0; n < kSamples; ++n) {
    Query q;
    q.s = int32_t(unit(rng) * 2 * one), q.t = int32_t(unit(rng) * 2 * one);
    const double rho = std::exp2(-2 + 7 * unit(rng)) / kSide, a = 2 * pi * unit(rng), r = 1 + unit(rng);
    q.d = {std::llround(rho * std::cos(a) * one), std::llround(rho * std::sin(a) * one),
           std::llround(-rho / r * std::sin(a) * one), std::llround(rho / r * std::cos(a) * one)};
    out.push_back(q);
  }
  return out;
}

// The golden arithmetic (texel_quad, filter_texels, blend_levels) at the exact level of
// detail, lambda rounded to s.8: what the sampler gives without the LOD approximation.
Rgba8 golden_at_exact_lod(const std::vector<MipLevel>& chain, const Query& q, TexFilter f) {
  const LevelChoice c = choose_levels(int32_t(std::lround(std::max(exact_lambda(q), -64.0) * 256)), 0,
                                      int(chain.size()), f);
  const auto level = [&](int k) {
    const MipLevel& l = chain[size_t(k)];
    const TexelQuad tq = texel_quad(q.s, q.t, l.width, l.height, kF, f != TexFilter::Nearest, TexWrap::Repeat,
                                    TexWrap::Repeat);
    std::array<Rgba8, 4> texels{};
    for (size_t n = 0; n < size_t(tq.count); ++n) texels[n] = l.texel(tq.i[n], tq.j[n]);
    return filter_texels(tq, texels);
  };
  const Rgba8 c0 = level(c.level0);
  return c.level1 == c.level0 ? c0 : blend_levels(c0, level(c.level1), c.frac);
}

// One table row: golden (filter f, weight_bits, mipmaps; exact_lod: at the exact level of
// detail) against the exact filter.
void study_row(const char* name, TexFilter f, int weight_bits, bool mipmap, bool exact_lod = false) {
  const auto image = study_texture();
  const auto chain = texture_test::ref_chain(*image, TexelFormat::Rgba8888);
  const std::vector<RefImage> level0(chain.begin(), chain.begin() + 1);
  TextureParams p;
  p.weight_bits = weight_bits;
  TextureUnit unit(p);
  TextureState ts;
  ts.image = image;
  ts.filter = f;
  ts.env = TexEnv::Replace;
  ts.mipmap = mipmap;
  double sum[3] = {}, worst[3] = {}, sq = 0;
  const auto queries = study_queries();
  const std::vector<MipLevel> golden_chain = build_mip_chain(*image, TexelFormat::Rgba8888, true);
  for (const Query& q : queries) {
    Fragment frag;
    frag.s = q.s, frag.t = q.t;
    const Fragment g = unit.shade(frag, q.d, ts, kF);
    const Rgba8 x = exact_lod ? golden_at_exact_lod(golden_chain, q, f) : Rgba8{g.r, g.g, g.b, 255};
    const auto e = exact_sample(mipmap ? chain : level0, q, f);
    const double got[3] = {double(x[0]), double(x[1]), double(x[2])};
    for (size_t ch = 0; ch < 3; ++ch) {
      const double err = std::fabs(got[ch] - e[ch]);
      sum[ch] += err, worst[ch] = std::max(worst[ch], err), sq += err * err;
    }
  }
  const double n = double(queries.size());
  std::printf("| %s | %d | %.3f / %.3f / %.3f | %.2f / %.2f / %.2f | %.1f |\n", name, weight_bits, sum[0] / n,
              sum[1] / n, sum[2] / n, worst[0], worst[1], worst[2], 10 * std::log10(255.0 * 255.0 / (sq / (3 * n))));
}

TEST(TextureStudy, DISABLED_FilterErrorAgainstExact) {
  std::printf("| filter | weight bits | mean abs error R / G / B | max abs error R / G / B | PSNR dB |\n");
  std::printf("|---|---:|---|---|---:|\n");
  study_row("nearest, mipmaps", TexFilter::Nearest, 8, true);
  study_row("bilinear, mipmaps", TexFilter::Bilinear, 8, true);
  study_row("trilinear", TexFilter::Trilinear, 8, true);
  study_row("nearest, mipmaps, exact LOD", TexFilter::Nearest, 8, true, true);
  study_row("bilinear, mipmaps, exact LOD", TexFilter::Bilinear, 8, true, true);
  study_row("trilinear, exact LOD", TexFilter::Trilinear, 8, true, true);
  for (int bits = 8; bits >= 1; --bits) study_row("bilinear, level 0", TexFilter::Bilinear, bits, false);
}

}  // namespace
}  // namespace rastsim
