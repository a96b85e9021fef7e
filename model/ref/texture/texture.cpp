// SPDX-License-Identifier: Apache-2.0
#include "ref/texture/texture.h"

#include <algorithm>
#include <bit>

namespace rastsim {

const char* to_string(TexFilter f) {
  switch (f) {
    case TexFilter::Nearest: return "nearest";
    case TexFilter::Bilinear: return "bilinear";
    case TexFilter::Trilinear: return "trilinear";
  }
  return "?";
}

int texel_bytes(TexelFormat f) {
  switch (f) {
    case TexelFormat::Rgba8888: return 4;
    case TexelFormat::Rgb565: return 2;
    case TexelFormat::L8: return 1;
  }
  return 4;
}

namespace {
// c (0..255) to n bits rounded to nearest (c (2^n - 1) / 255 is never a tie).
unsigned quantize(uint8_t c, int n) { return (unsigned(c) * ((1u << n) - 1) + 127) / 255; }
// An n-bit channel q back to 8 bits by bit replication (n >= 4).
uint8_t expand(unsigned q, int n) { return static_cast<uint8_t>((q << (8 - n)) | (q >> (2 * n - 8))); }
}  // namespace

uint32_t encode_texel(const Rgba8& c, TexelFormat f) {
  switch (f) {
    case TexelFormat::Rgba8888:
      return uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16 | uint32_t(c[3]) << 24;
    case TexelFormat::Rgb565: return quantize(c[0], 5) << 11 | quantize(c[1], 6) << 5 | quantize(c[2], 5);
    case TexelFormat::L8: return (77u * c[0] + 150u * c[1] + 29u * c[2] + 128u) >> 8;
  }
  return 0;
}

Rgba8 decode_texel(uint32_t stored, TexelFormat f) {
  switch (f) {
    case TexelFormat::Rgba8888:
      return {uint8_t(stored), uint8_t(stored >> 8), uint8_t(stored >> 16), uint8_t(stored >> 24)};
    case TexelFormat::Rgb565:
      return {expand((stored >> 11) & 31u, 5), expand((stored >> 5) & 63u, 6), expand(stored & 31u, 5), 255};
    case TexelFormat::L8: {
      const auto l = uint8_t(stored);
      return {l, l, l, 255};
    }
  }
  return {};
}

Rgba8 to_texel_format(const Rgba8& c, TexelFormat f) { return decode_texel(encode_texel(c, f), f); }

namespace {
MipLevel level_in_format(int w, int h, std::vector<uint8_t> rgba, TexelFormat f) {
  for (size_t k = 0; k + 3 < rgba.size(); k += 4) {
    const Rgba8 c = to_texel_format({rgba[k], rgba[k + 1], rgba[k + 2], rgba[k + 3]}, f);
    std::copy(c.begin(), c.end(), rgba.begin() + std::ptrdiff_t(k));
  }
  return {w, h, std::move(rgba)};
}

// The box-filtered level below `up` (see build_mip_chain), before the format.
std::vector<uint8_t> box_filter(const MipLevel& up, int w, int h) {
  std::vector<uint8_t> out(size_t(w) * size_t(h) * 4);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int i0 = std::min(2 * i, up.width - 1), i1 = std::min(2 * i + 1, up.width - 1);
      const int j0 = std::min(2 * j, up.height - 1), j1 = std::min(2 * j + 1, up.height - 1);
      const Rgba8 a = up.texel(i0, j0), b = up.texel(i1, j0), c = up.texel(i0, j1), d = up.texel(i1, j1);
      for (size_t ch = 0; ch < 4; ++ch)
        out[(size_t(j) * size_t(w) + size_t(i)) * 4 + ch] =
            static_cast<uint8_t>((unsigned(a[ch]) + b[ch] + c[ch] + d[ch] + 2) >> 2);
    }
  return out;
}
}  // namespace

std::vector<MipLevel> build_mip_chain(const TextureImage& image, TexelFormat f, bool mipmap) {
  std::vector<MipLevel> chain;
  chain.push_back(level_in_format(image.width, image.height, image.rgba, f));
  while (mipmap && (chain.back().width > 1 || chain.back().height > 1)) {
    const MipLevel& up = chain.back();
    const int w = std::max(1, up.width >> 1), h = std::max(1, up.height >> 1);
    chain.push_back(level_in_format(w, h, box_filter(up, w, h), f));
  }
  return chain;
}

uint64_t lod_length(int64_t a, int64_t b) {
  const uint64_t x = a < 0 ? uint64_t(-a) : uint64_t(a), y = b < 0 ? uint64_t(-b) : uint64_t(b);
  return std::max(x, y) + (std::min(x, y) >> 1);
}

int32_t log2_fixed8(uint64_t x) {
  const int n = std::bit_width(x) - 1;
  const uint64_t frac = n >= 8 ? (x >> (n - 8)) & 255 : (x << (8 - n)) & 255;
  return int32_t(n) * 256 + int32_t(frac);
}

int32_t texture_lod(const QuadDerivatives& d, int width, int height, int frac_bits) {
  const uint64_t rho = std::max(lod_length(d.dsdx * width, d.dtdx * height), lod_length(d.dsdy * width, d.dtdy * height));
  if (rho == 0) return kLodMinusInfinity;
  return log2_fixed8(rho) - frac_bits * 256;
}

LevelChoice choose_levels(int32_t lambda, int32_t bias, int levels, TexFilter filter) {
  const int32_t top = (levels - 1) * 256;
  const int32_t l = std::clamp(lambda + bias, 0, top);
  if (filter != TexFilter::Trilinear) {
    const int k = (l + 127) >> 8;
    return {k, k, 0};
  }
  const int k = l >> 8;
  const int frac = l & 255;
  return {k, frac ? std::min(k + 1, levels - 1) : k, frac};
}

int wrap_texel(int64_t i, int n, TexWrap w) {
  switch (w) {
    case TexWrap::Repeat: return int(((i % n) + n) % n);
    case TexWrap::Clamp: return int(std::clamp<int64_t>(i, 0, n - 1));
    case TexWrap::Mirror: {
      const int64_t m = ((i % (2 * int64_t(n))) + 2 * int64_t(n)) % (2 * int64_t(n));
      return int(m < n ? m : 2 * int64_t(n) - 1 - m);
    }
  }
  return 0;
}

namespace {
// One axis: nearest index, or the bilinear pair's first index and weight (see texel_quad).
struct AxisTexel {
  int64_t i0 = 0;
  int weight = 0;
};
AxisTexel axis_texel(int32_t s, int n, int frac_bits, bool bilinear, int weight_bits) {
  const int64_t u = int64_t(s) * n;  // 2^-F texels
  if (!bilinear) return {u >> frac_bits, 0};
  // u - 1/2 rounded to B = weight_bits fraction bits, ties up: floor((u - 1/2) 2^B + 1/2),
  // all in 2^-(F + B) texels (|u| < 2^45, so the shifted terms stay below 2^54).
  const int b = weight_bits;
  const int64_t ub = ((u << b) - (int64_t{1} << (frac_bits + b - 1)) + (int64_t{1} << (frac_bits - 1))) >> frac_bits;
  return {ub >> b, int(ub & ((int64_t{1} << b) - 1)) << (kMaxWeightBits - b)};  // weight in 1/256
}
}  // namespace

TexelQuad texel_quad(int32_t s, int32_t t, int width, int height, int frac_bits, bool bilinear, TexWrap wrap_s,
                     TexWrap wrap_t, int weight_bits) {
  const AxisTexel a = axis_texel(s, width, frac_bits, bilinear, weight_bits);
  const AxisTexel b = axis_texel(t, height, frac_bits, bilinear, weight_bits);
  TexelQuad q;
  if (!bilinear) {
    q.i[0] = wrap_texel(a.i0, width, wrap_s);
    q.j[0] = wrap_texel(b.i0, height, wrap_t);
    return q;
  }
  q.count = 4;
  const int i0 = wrap_texel(a.i0, width, wrap_s), i1 = wrap_texel(a.i0 + 1, width, wrap_s);
  const int j0 = wrap_texel(b.i0, height, wrap_t), j1 = wrap_texel(b.i0 + 1, height, wrap_t);
  q.i = {i0, i1, i0, i1};
  q.j = {j0, j0, j1, j1};
  q.alpha = a.weight;
  q.beta = b.weight;
  return q;
}

Rgba8 filter_texels(const TexelQuad& q, const std::array<Rgba8, 4>& texels) {
  if (q.count == 1) return texels[0];
  const uint32_t a = uint32_t(q.alpha), b = uint32_t(q.beta);
  const uint32_t w[4] = {(256 - a) * (256 - b), a * (256 - b), (256 - a) * b, a * b};
  Rgba8 out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    uint32_t sum = 1u << 15;
    for (size_t k = 0; k < 4; ++k) sum += w[k] * texels[k][ch];
    out[ch] = static_cast<uint8_t>(sum >> 16);
  }
  return out;
}

Rgba8 blend_levels(const Rgba8& c0, const Rgba8& c1, int frac) {
  Rgba8 out{};
  for (size_t ch = 0; ch < 4; ++ch)
    out[ch] = static_cast<uint8_t>((unsigned(c0[ch]) * unsigned(256 - frac) + unsigned(c1[ch]) * unsigned(frac) + 128) >> 8);
  return out;
}

std::array<uint8_t, 3> texenv_combine(TexEnv env, const Rgba8& tex, const std::array<uint8_t, 3>& color) {
  std::array<uint8_t, 3> out{};
  for (size_t ch = 0; ch < 3; ++ch) {
    const unsigned t = tex[ch], c = color[ch], a = tex[3];
    switch (env) {
      case TexEnv::Replace: out[ch] = static_cast<uint8_t>(t); break;
      case TexEnv::Modulate: out[ch] = static_cast<uint8_t>((t * c + 127) / 255); break;
      case TexEnv::Decal: out[ch] = static_cast<uint8_t>((c * (255 - a) + t * a + 127) / 255); break;
    }
  }
  return out;
}

}  // namespace rastsim
