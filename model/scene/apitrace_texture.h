// SPDX-License-Identifier: Apache-2.0
// GL texture objects as rastsim import-apitrace tracks them (docs/workloads.md,
// "Textures"): glGenTextures/glBindTexture/glActiveTexture bindings, glTexImage2D and
// glTexSubImage2D level 0 (RGBA, RGB, LUMINANCE, LUMINANCE_ALPHA, ALPHA of unsigned
// bytes, rows padded to GL_UNPACK_ALIGNMENT) decoded to RGBA8, glTexParameter{i,f}
// (filters, wraps, LOD bias) and glGenerateMipmap (and its EXT, OES names); a texture
// compressed, copied from the framebuffer or attached to a framebuffer object is marked
// unusable (draws sampling it are refused); and the trace's texture state
// (`texfilter`, `mipmap`, `texwrap`) a texture's parameters map to, or why none does.
//
// Texel origin: GL's first row of pixels is t = 0 (drawn at the bottom of GL's image
// space); the trace's t = 0 is the image file's first (top) row (docs/texture.md). The
// RGBA8 rows are kept in GL's order and written to the file in that order, so a texture
// coordinate passes unchanged (s, t -> s, t, bit for bit) and the file, viewed, shows
// the image upside down relative to GL's picture of it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace rastsim::apitrace {

struct Call;
struct Value;

struct GlTexture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // level 0, width x height x 4, row 0 = GL's first row (t = 0)
  int version = 0;            // 1 at the first level-0 image, +1 at each later one or sub-image
  uint64_t image_call = 0;    // the call that last changed level 0
  std::string unusable;       // why level 0 cannot be imported ("" when it can)
  // GL's initial parameters (GL ES 2.0 3.7.12).
  std::string min_filter = "GL_NEAREST_MIPMAP_LINEAR", mag_filter = "GL_LINEAR";
  std::string wrap_s = "GL_REPEAT", wrap_t = "GL_REPEAT";
  enum class Mips { None, Generated, Uploaded } mips = Mips::None;
  double lod_bias = 0;  // GL_TEXTURE_LOD_BIAS (desktop GL), levels
};

// One context's texture objects, GL_TEXTURE_2D bindings per unit and unpack alignment.
struct TextureTable {
  std::map<uint32_t, GlTexture> textures;
  std::map<int64_t, uint32_t> bound;  // texture unit -> texture bound to GL_TEXTURE_2D
  int64_t active_unit = 0;
  int64_t unpack_alignment = 4;       // GL_UNPACK_ALIGNMENT, bytes
};

// The texture calls (above) applied to `t`; false for any other call. `bytes_of` reads a
// blob argument; a malformed call throws SceneError("name:line: call N F: what").
bool texture_call(TextureTable& t, const Call& c, const std::string& name,
                  const std::function<std::string(const Value&)>& bytes_of);

// `pixels` (rows of w texels of `format` and `type`, each row padded to `align` bytes) to
// RGBA8: RGB -> (R, G, B, 255), LUMINANCE -> (L, L, L, 255), LUMINANCE_ALPHA ->
// (L, L, L, A), ALPHA -> (0, 0, 0, A) as GL expands them. Empty, with `why`, for another
// format or type or too few bytes.
std::vector<uint8_t> pixels_to_rgba(const std::string& format, const std::string& type, int w, int h,
                                    int64_t align, const std::string& pixels, std::string& why);

// The trace state of a texture's parameters. min/mag NEAREST -> nearest, LINEAR ->
// bilinear (mipmap off); NEAREST_MIPMAP_NEAREST with mag NEAREST -> nearest, mipmap on;
// LINEAR_MIPMAP_NEAREST with mag LINEAR -> bilinear, mipmap on; LINEAR_MIPMAP_LINEAR with
// mag LINEAR -> trilinear. rastsim has one filter for magnification and minification,
// so other pairs (and NEAREST_MIPMAP_LINEAR) are refused, as is a mipmap filter without
// mip levels (GL's texture is incomplete and samples black). Wraps: REPEAT -> repeat,
// CLAMP_TO_EDGE -> clamp, MIRRORED_REPEAT -> mirror.
struct SamplerState {
  bool ok = false;
  std::string why;  // when !ok
  std::string filter, wrap_s, wrap_t;
  bool mipmap = false;
};
SamplerState sampler_state(const GlTexture& t);

}  // namespace rastsim::apitrace
