// SPDX-License-Identifier: Apache-2.0
// The texture unit's golden arithmetic (docs/texture.md has every rule, width and
// rounding): texel formats, the mip chain, level of detail from a 2x2 quad's coordinate
// derivatives, texel addressing with wrap, nearest / bilinear / trilinear filtering and
// the texenv combine with the interpolated colour. Integers only, bit-exact; the tests'
// independent sampler (tb/texture) derives the same values in double arithmetic from
// the D3D11/Vulkan texel-address rules.
//
// Coordinates: (s, t) = (0, 0) is the top-left corner of the image as stored in its file
// (its first row is t = 0), one repeat spans 0..1, texel i's centre is at (i + 0.5) / W.
// s and t arrive in raw interp.texcoord_format units (F fraction bits: value 2^-F repeats).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ref/memory/memory_params.h"

namespace rastsim {

enum class TexFilter { Nearest, Bilinear, Trilinear };  // `texfilter`
enum class TexWrap { Repeat, Clamp, Mirror };            // `texwrap`, per axis
enum class TexEnv { Replace, Modulate, Decal };          // `texenv`
enum class TexelFormat { Rgba8888, Rgb565, L8 };         // texture.format
enum class TexLayout { Linear, Tiled, Morton };          // texture.layout

inline constexpr int kTexFilters = 3;  // TexFilter's enumerators (texture_samples per mode)
const char* to_string(TexFilter f);

// A decoded image file: RGBA8, row-major, row 0 the file's first (top) row.
struct TextureImage {
  std::string name;  // the file, for messages
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width x height x 4
};

// The texture state a primitives command is drawn with (trace commands `bindtexture`,
// `texfilter`, `texwrap`, `texenv`, `mipmap`, `texlod_bias`; an OBJ material's map_Kd).
// No image bound: untextured, the fragment's colour goes to the ROP unchanged.
struct TextureState {
  std::shared_ptr<const TextureImage> image;
  TexFilter filter = TexFilter::Bilinear;
  TexWrap wrap_s = TexWrap::Repeat, wrap_t = TexWrap::Repeat;
  TexEnv env = TexEnv::Modulate;
  bool mipmap = false;
  int32_t lod_bias = 0;  // level-of-detail bias, s.8 fixed point (1/256 of a level), |B| <= kMaxLodBias levels
  bool enabled() const { return image != nullptr; }
};

// The texture unit's parameters (keys texture.*, config/texture_config.h).
// The bilinear weight's widest fraction: 8 bits, so that a weight 0..256 is 9 bits and a
// texel times two weights fits 25 bits (filter_texels' 32-bit sums).
inline constexpr int kMaxWeightBits = 8;

struct TextureParams {
  TexelFormat format = TexelFormat::Rgba8888;
  TexLayout layout = TexLayout::Linear;
  uint64_t base = 0;  // bytes: the first texture's address (multiple of 4096)
  int weight_bits = kMaxWeightBits;  // texture.weight_bits: bilinear weight fraction bits, 1..8
  CacheParams cache;  // texture.cache_bytes (0: no cache), texture.ways, texture.line_bytes
};

// texlod_bias B's range, levels: [-kMaxLodBias, kMaxLodBias] (s.8: 256 x that).
inline constexpr int kMaxLodBias = 16;

using Rgba8 = std::array<uint8_t, 4>;

// Bytes of one stored texel: 4 (RGBA8888), 2 (RGB565), 1 (L8).
int texel_bytes(TexelFormat f);
// An RGBA8 colour stored in format f and read back as RGBA8 (docs/texture.md, "Texel
// formats"): RGB565 rounds each channel to nearest, (c (2^n - 1) + 127) / 255, and
// expands by bit replication; L8 is (77 R + 150 G + 29 B + 128) >> 8; both alpha 255.
// It is decode_texel(encode_texel(c, f), f).
Rgba8 to_texel_format(const Rgba8& c, TexelFormat f);
// A texel as stored in memory: texel_bytes(f) bytes, little-endian (byte k = bits
// [8k +: 8]). RGBA8888: R [7:0], G [15:8], B [23:16], A [31:24]; RGB565: B5 [4:0], G6
// [10:5], R5 [15:11] (the rounding above); L8: L [7:0]. Bits above texel_bytes(f) are 0.
uint32_t encode_texel(const Rgba8& c, TexelFormat f);
// The stored bits (the low texel_bytes(f) bytes of `stored`; the rest ignored) read back
// as RGBA8: what the texture cache's RTL decodes (rtl/rast_texture_cache.sv).
Rgba8 decode_texel(uint32_t stored, TexelFormat f);

// One mip level: width x height texels, already in the texel format (as RGBA8).
struct MipLevel {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  Rgba8 texel(int i, int j) const {
    const size_t k = (size_t(j) * size_t(width) + size_t(i)) * 4;
    return {rgba[k], rgba[k + 1], rgba[k + 2], rgba[k + 3]};
  }
};

// Level 0 is the image in format f; with `mipmap`, level k + 1 is max(1, W >> 1) x
// max(1, H >> 1), texel (i, j) the box average (a + b + c + d + 2) >> 2 per channel of
// level k's texels (2i + di, 2j + dj), di, dj in {0, 1} clamped to level k's last column
// and row, stored in f again; down to 1 x 1.
std::vector<MipLevel> build_mip_chain(const TextureImage& image, TexelFormat f, bool mipmap);

// The texture-coordinate derivatives of a 2x2 quad, raw interp.texcoord_format units:
// coarse, as D3D11 ddx_coarse / ddy_coarse: the top row's right minus left pixel, the
// left column's bottom minus top pixel, the same for all four pixels.
struct QuadDerivatives {
  int64_t dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
};

// The length approximation of (a, b): max(|a|, |b|) + (min(|a|, |b|) >> 1) (within the
// Vulkan bounds max <= len <= |a| + |b|).
uint64_t lod_length(int64_t a, int64_t b);
// floor(log2(x) 2^8) with log2 approximated piecewise-linearly between powers of two:
// the leading one's position n, then the next 8 bits as the fraction (x > 0).
int32_t log2_fixed8(uint64_t x);
// The smallest level of detail: a quad whose coordinates do not change (rho = 0).
inline constexpr int32_t kLodMinusInfinity = -(1 << 24);
// The unclamped, unbiased level of detail lambda, s.8 fixed point, of a level-0 texture
// W x H texels: rho = max(lod_length(dsdx W, dtdx H), lod_length(dsdy W, dtdy H)) in
// 2^-F texels, lambda = log2_fixed8(rho) - F 2^8.
int32_t texture_lod(const QuadDerivatives& d, int width, int height, int frac_bits);

// The mip levels a sample reads and the weight of the second (trilinear).
struct LevelChoice {
  int level0 = 0, level1 = 0;  // level1 == level0: one level
  int frac = 0;                // weight of level1, 0..255 (/256)
};
// lambda + bias clamped to [0, (levels - 1) 2^8] (levels = 1 without mipmaps); nearest
// and bilinear take the nearest level, ties to the finer ((lambda + 127) >> 8), trilinear
// levels floor(lambda) and the next, weighted by lambda's fraction bits.
LevelChoice choose_levels(int32_t lambda, int32_t bias, int levels, TexFilter filter);

// Wrap of texel index i on an axis of n texels: repeat (i mod n), clamp to edge
// (clamp(i, 0, n - 1)), mirrored repeat (m = i mod 2n; m < n ? m : 2n - 1 - m).
int wrap_texel(int64_t i, int n, TexWrap w);

// The texels a sample reads on one level, in fetch order, and their bilinear weights.
struct TexelQuad {
  int count = 1;                  // 1 (nearest) or 4 (bilinear: (i0,j0), (i1,j0), (i0,j1), (i1,j1))
  std::array<int, 4> i{}, j{};    // wrapped texel indices
  int alpha = 0, beta = 0;        // bilinear weights of i1 and j1, 0..255 (/256)
};
// Nearest: i = floor(s W / 2^F) (the texel whose [i, i + 1) / W holds s). Bilinear:
// x = s W / 2^F - 1/2 rounded to nearest at B = weight_bits fraction bits, ties up
// (xB = floor(x 2^B + 1/2)), i0 = xB >> B, i1 = i0 + 1, alpha = (xB mod 2^B) 2^(8 - B)
// (in 1/256; a weight rounding up to a whole texel moves i0 on, alpha 0); t, H, j and
// beta alike. Each index wrapped on its own axis.
TexelQuad texel_quad(int32_t s, int32_t t, int width, int height, int frac_bits, bool bilinear, TexWrap wrap_s,
                     TexWrap wrap_t, int weight_bits = kMaxWeightBits);
// The filtered colour of a TexelQuad's texels: nearest the texel; bilinear per channel
// (T00 (256-a)(256-b) + T10 a (256-b) + T01 (256-a) b + T11 a b + 2^15) >> 16.
Rgba8 filter_texels(const TexelQuad& q, const std::array<Rgba8, 4>& texels);
// Trilinear: (c0 (256 - f) + c1 f + 128) >> 8 per channel.
Rgba8 blend_levels(const Rgba8& c0, const Rgba8& c1, int frac);

// The texenv combine of texture colour T with the fragment's colour C (alpha 255), per
// channel, every quotient rounded to nearest ((x + 127) / 255; x / 255 is never a tie):
// replace T; modulate T C / 255; decal (C (255 - Ta) + T Ta) / 255.
std::array<uint8_t, 3> texenv_combine(TexEnv env, const Rgba8& tex, const std::array<uint8_t, 3>& color);

}  // namespace rastsim
