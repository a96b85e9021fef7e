// SPDX-License-Identifier: Apache-2.0
// llvmpipe's sampler through OSMesa: one textured triangle a draw (osmesa_texture.h).
#include "osmesa_texture.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <stdexcept>

namespace rastsim::mesa {
namespace {

using TexClipControlFn = void (*)(GLenum origin, GLenum depth);

GLint gl_wrap(GlWrap w) {
  switch (w) {
    case GlWrap::Repeat: return GL_REPEAT;
    case GlWrap::Clamp: return GL_CLAMP_TO_EDGE;
    case GlWrap::Mirror: return GL_MIRRORED_REPEAT;
  }
  return GL_REPEAT;
}

}  // namespace

OsMesaTexture::OsMesaTexture(int width, int height)
    : width_(width), height_(height), buffer_(size_t(width) * size_t(height)) {
  ctx_ = create_llvmpipe_context();
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), buffer_.data(), GL_UNSIGNED_BYTE, width, height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  auto origin = reinterpret_cast<TexClipControlFn>(OSMesaGetProcAddress("glClipControl"));
  if (!origin) throw std::runtime_error("glClipControl not available (GL 4.5 / ARB_clip_control)");
  origin(GL_UPPER_LEFT, GL_ZERO_TO_ONE);  // y down, top-left rule: as OsMesaRenderer
  glViewport(-kViewport / 2, height - kViewport / 2, kViewport, kViewport);
  set_coverage_state(false);  // identity matrices, no blend, dither, depth or culling
  glShadeModel(GL_SMOOTH);
  glGenTextures(1, &tex_);
  glBindTexture(GL_TEXTURE_2D, tex_);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error during texture set-up");
}

OsMesaTexture::~OsMesaTexture() { OSMesaDestroyContext(static_cast<OSMesaContext>(ctx_)); }

std::vector<uint32_t> OsMesaTexture::draw(const TexturedTri& tri, const TexChain& tex, GlFilter filter,
                                          GlWrap wrap_s, GlWrap wrap_t) {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  // Row 0 of the upload is GL's t = 0 row, the reference's top (first) row: the same
  // (s, t) names the same texel in both, whatever the window's orientation.
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tex.base.width, tex.base.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               tex.base.rgba.data());
  for (size_t k = 0; k < tex.below.size(); ++k)
    glTexImage2D(GL_TEXTURE_2D, GLint(k + 1), GL_RGBA8, tex.below[k].width, tex.below[k].height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, tex.below[k].rgba.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(tex.below.size()));  // level 0 alone: no mipmaps
  const bool nearest = filter == GlFilter::Nearest, mip = !tex.below.empty();
  GLint min = mip ? (nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_NEAREST) : (nearest ? GL_NEAREST : GL_LINEAR);
  if (filter == GlFilter::Trilinear) min = mip ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, gl_wrap(wrap_s));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, gl_wrap(wrap_t));
  glClear(GL_COLOR_BUFFER_BIT);
  const float scale = 2.0f / (float(int64_t{1} << tri.tri.frac_bits) * float(kViewport));  // exact power of two
  glBegin(GL_TRIANGLES);
  for (size_t v = 0; v < 3; ++v) {
    glTexCoord2f(tri.s[v], tri.t[v]);
    glVertex3f(float(tri.tri.x[v]) * scale, float(tri.tri.y[v]) * scale, 0.0f);
  }
  glEnd();
  std::vector<uint32_t> gl_rows(buffer_.size());
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error while drawing a textured triangle");
  std::vector<uint32_t> rows(gl_rows.size());  // GL rows bottom first: flip to the scene's
  for (int r = 0; r < height_; ++r)
    std::copy_n(gl_rows.data() + size_t(height_ - 1 - r) * width_, width_, rows.data() + size_t(r) * width_);
  return rows;
}

}  // namespace rastsim::mesa
