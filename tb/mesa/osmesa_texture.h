// SPDX-License-Identifier: Apache-2.0
// llvmpipe's texture sampler through OSMesa, for the textured-triangle comparison
// (docs/texture.md, "Checks"): the window and coordinates as OsMesaRenderer (top-left
// origin, the power-of-two viewport that makes gallium's pixel coordinate the scene's
// exactly), no logic op, GL_TEXTURE_2D with GL_REPLACE (texenv replace: the fragment's
// colour is the filtered texel, so only the sampler is compared), mipmaps off or the
// reference's chain uploaded level by level.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "osmesa_renderer.h"

namespace rastsim::mesa {

// GL_NEAREST / GL_LINEAR, min and mag; Trilinear: GL_LINEAR_MIPMAP_LINEAR min, GL_LINEAR mag
// (mipmapped only).
enum class GlFilter { Nearest, Bilinear, Trilinear };
enum class GlWrap { Repeat, Clamp, Mirror };    // GL_REPEAT, GL_CLAMP_TO_EDGE, GL_MIRRORED_REPEAT

// One textured triangle: vertices on the 2^-frac_bits px grid (GridTri), each with its
// texture coordinate (s, t) in repeats, binary32; (0, 0) the top-left corner of the
// texture's row 0 (the first row uploaded, as the reference's first file row).
struct TexturedTri {
  GridTri tri;
  std::array<float, 3> s{}, t{};
};

// A texture: width x height RGBA8 texels, row 0 first.
struct TexImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};
// A texture and, mipmapped, its levels below level 0 (down to 1 x 1).
struct TexChain {
  TexImage base;
  std::vector<TexImage> below;  // empty: mipmaps off
};

class OsMesaTexture {
 public:
  OsMesaTexture(int width, int height);  // throws std::runtime_error when OSMesa fails
  ~OsMesaTexture();
  OsMesaTexture(const OsMesaTexture&) = delete;
  OsMesaTexture& operator=(const OsMesaTexture&) = delete;

  // The image of `tri` drawn alone over a clear colour of (0, 0, 0, 0), textured with
  // `tex` (filter and wrap on both axes; mipmapped: the nearest level,
  // GL_*_MIPMAP_NEAREST, or two levels blended for Trilinear), GL_REPLACE: RGBA8 per
  // pixel, row 0 at the top.
  std::vector<uint32_t> draw(const TexturedTri& tri, const TexChain& tex, GlFilter filter, GlWrap wrap_s,
                             GlWrap wrap_t);

 private:
  int width_, height_;
  void* ctx_ = nullptr;           // OSMesaContext
  std::vector<uint32_t> buffer_;  // OSMesa's colour buffer, RGBA8
  unsigned tex_ = 0;              // the one texture object
};

}  // namespace rastsim::mesa
