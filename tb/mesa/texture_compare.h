// SPDX-License-Identifier: Apache-2.0
// Textured triangles, reference model against llvmpipe (docs/texture.md, "Checks"):
// random small textures (1..16 texels a side, odd sides included), random triangles on
// the 1/256 px grid with random texture coordinates (multiples of 2^-10 in [-2, 3]
// repeats: exact in binary32 and in interp.texcoord_format), nearest or bilinear, every
// wrap pair, mipmaps off, texenv replace. Compared on interior pixels only: pixel centres
// farther than one coordinate LSB (1/256 px) from every edge, whose coverage the two
// rasterizers cannot decide differently.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "osmesa_texture.h"
#include "ref/raster_state.h"

namespace rastsim::mesa {

struct TexCase {
  TexturedTri tri;
  TexChain tex;  // mipmapped: the reference's chain (ref/texture build_mip_chain) uploaded level by level
  GlFilter filter = GlFilter::Nearest;
  GlWrap wrap_s = GlWrap::Repeat, wrap_t = GlWrap::Repeat;
};

// `count` cases of one filter in a width x height framebuffer; the same seed, the same
// cases. Mipmapped: textures of 1 to 32 texels a side, minified up to about 8 times.
std::vector<TexCase> make_texture_cases(uint64_t seed, int count, GlFilter filter, int width, int height,
                                        bool mipmap = false);

// Mipmapped: where the triangle's exact level of detail (log2 of the longer Euclidean
// derivative length, constant on an affine triangle) lies within this many levels of a
// rounding point k + 1/2, the approximations decide the level: the reference's is low by
// up to 0.086 (log2_fixed8) and high by up to 0.161 (the length, +11.8 %), docs/texture.md.
inline constexpr double kLodTieBand = 0.2;

// Where the exact texel coordinate u = s W (or v = t H; bilinear: u - 1/2) of a pixel
// centre lies within this many texels of a texel edge, rounding decides the texel: the
// reference rounds s once to 2^-F repeats (F = 20: 2^-16 texels at W = 16), llvmpipe
// interpolates s in binary32 (2^-22 relative: about 2^-16 texels at |s| = 3, W = 16). The
// band is wider than both together.
inline constexpr double kTexelTieBand = 1.0 / 4096;

// Trilinear: the levels of detail either sampler may use around the exact lambda
// (exact_lambda below): the reference's lies in [lambda - 0.086, lambda + 0.161] (the
// chord of log2_fixed8 low, the length approximation high: docs/texture.md) and its blend
// weight is truncated to 1/256 of a level; the band adds that step to both ends.
inline constexpr double kTrilinearBandLow = 0.086 + 1.0 / 256, kTrilinearBandHigh = 0.161 + 1.0 / 256;
// How far (LSB) a trilinear colour may lie outside the exact trilinear filter's range
// over that band: each level's rounded bilinear colour within 1.5 LSB of the exact one
// (the bilinear bound), blended (a convex combination: still within 1.5), rounded once more.
inline constexpr double kTrilinearSlack = 2.0;

struct TexCompareStats {
  uint64_t triangles = 0;
  uint64_t interior = 0;        // interior pixel centres compared
  uint64_t identical = 0;       // the same RGB
  uint64_t within_one = 0;      // different, every channel within 1 LSB
  uint64_t beyond_one = 0;      // some channel more than 1 LSB apart
  uint64_t near_texel_edge = 0; // of the different: u or v within kTexelTieBand of a texel edge
  uint64_t near_lod_tie = 0;    // of the different, mipmapped: the exact lambda within kLodTieBand of k + 1/2
  uint64_t unexplained = 0;     // of the different: neither near a texel edge nor a level tie
  int max_diff_off_tie = 0;     // the largest channel difference away from level ties
  uint64_t beyond_one_off_tie = 0;  // more than 1 LSB apart away from level ties
  int max_channel_diff = 0;
  // Bilinear: the largest |colour - exact bilinear filter| (double weights, unrounded) of
  // any channel, reference and llvmpipe.
  double ref_max_error = 0, llvmpipe_max_error = 0;
  // Trilinear: pixels whose colour lies more than kTrilinearSlack outside the exact
  // trilinear range over the lambda band [lambda - kTrilinearBandLow, lambda +
  // kTrilinearBandHigh] (rastsim: its stated bound; llvmpipe: whether its level of detail
  // falls in the same band); the pixels whose two colours are more than that range plus
  // 1 LSB apart; the largest range.
  uint64_t outside_band_ref = 0, outside_band_llvmpipe = 0, beyond_range_plus_one = 0;
  double max_band_spread = 0, max_outside_ref = 0, max_outside_llvmpipe = 0;
  // The largest difference beyond the band's range (|rastsim - llvmpipe| - range), and the
  // negative control: rastsim pixels outside the band moved half a level finer (lambda -
  // 1/2), as a level of detail off by half a level would be: must be many.
  double max_diff_beyond_spread = 0;
  uint64_t outside_shifted_band_ref = 0;
  TexCompareStats& operator+=(const TexCompareStats& o);
};

// Renders `c` by the reference (render_scene, `st`) and by llvmpipe and compares the
// interior pixels; describes up to max_report differences in `report`.
TexCompareStats compare_textured(const TexCase& c, const RasterState& st, OsMesaTexture& gl,
                                 std::vector<std::string>& report, size_t max_report);

}  // namespace rastsim::mesa
