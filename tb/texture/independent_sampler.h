// SPDX-License-Identifier: Apache-2.0
// The tests' independent sampler: written from the D3D11/Vulkan texel-address rules and
// docs/texture.md's stated roundings in plain double arithmetic (every value below is a
// dyadic rational of fewer than 53 bits, so each double is exact and each floor is the
// exact one), sharing no code with ref/texture. Slow on purpose: a texel at a time.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ref/texture/texture.h"

namespace rastsim::texture_test {

struct RefImage {
  int w = 0, h = 0;
  std::vector<std::array<double, 4>> texel;  // row-major, channel values 0..255
  const std::array<double, 4>& at(int i, int j) const { return texel[size_t(j) * size_t(w) + size_t(i)]; }
};

// A channel stored in n bits (round to nearest of c (2^n - 1) / 255) and read back by
// repeating its bits: the top bits again below (c_n 2^(8-n) + floor(c_n / 2^(2n-8))).
inline double stored_bits(double c, int n) {
  const double top = std::pow(2.0, n) - 1;
  const double q = std::floor(c * top / 255.0 + 0.5);
  return q * std::pow(2.0, 8 - n) + std::floor(q / std::pow(2.0, 2 * n - 8));
}

inline std::array<double, 4> ref_format(const std::array<double, 4>& c, TexelFormat f) {
  switch (f) {
    case TexelFormat::Rgba8888: return c;
    case TexelFormat::Rgb565: return {stored_bits(c[0], 5), stored_bits(c[1], 6), stored_bits(c[2], 5), 255};
    case TexelFormat::L8: {
      // Luminance weights 0.30078125, 0.5859375, 0.11328125 (77, 150, 29 of 256), to nearest, ties up.
      const double l = std::floor(c[0] * 0.30078125 + c[1] * 0.5859375 + c[2] * 0.11328125 + 0.5);
      return {l, l, l, 255};
    }
  }
  return c;
}

// The mip chain: level 0 in the format, each next level half the size (at least 1),
// each texel the mean of the 2x2 texels above it (the edge texel repeated when the level
// above is one texel wide or high), rounded to nearest with ties up, then stored in the
// format again.
inline std::vector<RefImage> ref_chain(const TextureImage& img, TexelFormat f) {
  std::vector<RefImage> chain(1);
  RefImage& l0 = chain[0];
  l0.w = img.width;
  l0.h = img.height;
  for (size_t k = 0; k < size_t(img.width) * size_t(img.height); ++k)
    l0.texel.push_back(ref_format({double(img.rgba[4 * k]), double(img.rgba[4 * k + 1]), double(img.rgba[4 * k + 2]),
                                   double(img.rgba[4 * k + 3])},
                                  f));
  while (chain.back().w > 1 || chain.back().h > 1) {
    const RefImage up = chain.back();
    RefImage next;
    next.w = std::max(1, up.w / 2);
    next.h = std::max(1, up.h / 2);
    for (int j = 0; j < next.h; ++j)
      for (int i = 0; i < next.w; ++i) {
        std::array<double, 4> c{};
        for (int ch = 0; ch < 4; ++ch) {
          double sum = 0;
          for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) sum += up.at(std::min(2 * i + di, up.w - 1), std::min(2 * j + dj, up.h - 1))[size_t(ch)];
          c[size_t(ch)] = std::floor(sum / 4 + 0.5);
        }
        next.texel.push_back(ref_format(c, f));
      }
    chain.push_back(std::move(next));
  }
  return chain;
}

// Vulkan's wrap of an integer texel coordinate (the spec's formulas: repeat (i mod size),
// mirrored repeat (size - 1) - mirror((i mod 2 size) - size), mirror(a) = a >= 0 ? a :
// -(1 + a); clamp to edge).
inline int ref_wrap(double i, int n, TexWrap w) {
  const auto mod = [](double a, double b) { return a - b * std::floor(a / b); };
  switch (w) {
    case TexWrap::Repeat: return int(mod(i, n));
    case TexWrap::Clamp: return int(std::clamp(i, 0.0, double(n - 1)));
    case TexWrap::Mirror: {
      const double a = mod(i, 2.0 * n) - n;
      return int((n - 1) - (a >= 0 ? a : -(1 + a)));
    }
  }
  return 0;
}

struct RefQuery {
  int32_t s = 0, t = 0;                 // raw, F fraction bits
  int64_t dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
  int frac_bits = 20;
  int weight_bits = 8;                  // texture.weight_bits
  std::array<double, 3> color{};        // the fragment's colour
};

// One level's filtered colour at (s, t): nearest, the texel holding the point (u = s W);
// bilinear, x = u - 1/2 rounded to the nearest multiple of 2^-B texel (B the weight bits;
// ties up, to the multiple to the right), the two texels either side of it weighted by
// its distance from them, the weighted sum rounded to nearest with ties up.
inline std::array<double, 4> ref_level(const RefImage& l, const RefQuery& q, const TextureState& ts) {
  const double scale = std::pow(2.0, -q.frac_bits);
  const double u = q.s * scale * l.w, v = q.t * scale * l.h;
  if (ts.filter == TexFilter::Nearest) return l.at(ref_wrap(std::floor(u), l.w, ts.wrap_s), ref_wrap(std::floor(v), l.h, ts.wrap_t));
  const double step = std::pow(2.0, q.weight_bits);
  const double x = std::floor((u - 0.5) * step + 0.5) / step, y = std::floor((v - 0.5) * step + 0.5) / step;
  const double i0 = std::floor(x), j0 = std::floor(y);
  const double a = x - i0, b = y - j0;
  std::array<double, 4> out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    double sum = 0;
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di)
        sum += (di ? a : 1 - a) * (dj ? b : 1 - b) *
               l.at(ref_wrap(i0 + di, l.w, ts.wrap_s), ref_wrap(j0 + dj, l.h, ts.wrap_t))[ch];
    out[ch] = std::floor(sum + 0.5);
  }
  return out;
}

// The level of detail: rho in texels from the approximate length max + min / 2 (the half
// truncated to the coordinates' LSB), lambda = log2 approximated between powers of two
// (rho = 2^n (1 + m), lambda = n + m truncated to 1/256), plus the bias, clamped to the
// chain; nearest and bilinear the nearest level (ceil(lambda + 1/2) - 1, ties to the finer),
// trilinear floor(lambda) and the next weighted by lambda's fraction.
inline std::array<double, 3> ref_sample(const std::vector<RefImage>& chain, const RefQuery& q, const TextureState& ts) {
  const double lsb = std::pow(2.0, -q.frac_bits);
  const double w = chain[0].w, h = chain[0].h;
  const auto len = [&](double a, double b) {
    a = std::fabs(a), b = std::fabs(b);
    return std::max(a, b) + std::floor(std::min(a, b) / 2 / lsb) * lsb;
  };
  const double rho = std::max(len(q.dsdx * lsb * w, q.dtdx * lsb * h), len(q.dsdy * lsb * w, q.dtdy * lsb * h));
  const int levels = ts.mipmap ? int(chain.size()) : 1;
  double lambda = -1e9;
  if (rho > 0 && levels > 1) {
    int e = 0;
    const double m = std::frexp(rho, &e);  // rho = m 2^e, m in [1/2, 1)
    lambda = (e - 1) + std::floor((2 * m - 1) * 256) / 256;
  } else if (levels == 1) {
    lambda = 0;
  }
  const double l = std::clamp(lambda + ts.lod_bias / 256.0, 0.0, double(levels - 1));
  std::array<double, 4> tex{};
  if (ts.filter != TexFilter::Trilinear) {
    tex = ref_level(chain[size_t(std::ceil(l + 0.5) - 1)], q, ts);
  } else {
    const double k = std::floor(l), f = l - k;
    const auto c0 = ref_level(chain[size_t(k)], q, ts);
    const auto c1 = f > 0 ? ref_level(chain[size_t(std::min(k + 1, double(levels - 1)))], q, ts) : c0;
    for (size_t ch = 0; ch < 4; ++ch) tex[ch] = std::floor(c0[ch] * (1 - f) + c1[ch] * f + 0.5);
  }
  std::array<double, 3> out{};
  for (size_t ch = 0; ch < 3; ++ch) {
    const double t = tex[ch], c = q.color[ch], a = tex[3];
    const double v = ts.env == TexEnv::Replace ? t : ts.env == TexEnv::Modulate ? t * c / 255 : (c * (255 - a) + t * a) / 255;
    out[ch] = std::floor(v + 0.5);
  }
  return out;
}

}  // namespace rastsim::texture_test
