// SPDX-License-Identifier: Apache-2.0
// llvmpipe through OSMesa for clip-space triangles (see osmesa_clip.h).
#include "osmesa_clip.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <stdexcept>

#include "osmesa_renderer.h"

namespace rastsim::mesa {
namespace {

using ClipControlFn = void (*)(GLenum origin, GLenum depth);

}  // namespace

OsMesaClipRenderer::OsMesaClipRenderer(int width, int height)
    : width_(width), height_(height), buffer_(size_t(width) * size_t(height)) {
  ctx_ = create_llvmpipe_context();
  make_current();
  auto clip_control = reinterpret_cast<ClipControlFn>(OSMesaGetProcAddress("glClipControl"));
  if (!clip_control) throw std::runtime_error("glClipControl not available (GL 4.5 / ARB_clip_control)");
  clip_control(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  GLint origin = 0, depth_mode = 0;
  glGetIntegerv(GL_CLIP_ORIGIN, &origin);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &depth_mode);
  if (origin != GL_UPPER_LEFT || depth_mode != GL_ZERO_TO_ONE)
    throw std::runtime_error("glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE) did not take effect");
  set_coverage_state(false);
  glShadeModel(GL_SMOOTH);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_COLOR_LOGIC_OP);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error during set-up");
}

OsMesaClipRenderer::~OsMesaClipRenderer() { OSMesaDestroyContext(static_cast<OSMesaContext>(ctx_)); }

void OsMesaClipRenderer::make_current() {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

std::string OsMesaClipRenderer::renderer_name() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}
std::string OsMesaClipRenderer::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

std::vector<uint32_t> OsMesaClipRenderer::render(const std::vector<ClipTri>& tris, const ViewRect& vp) {
  make_current();
  // GL's window y runs up from the bottom row: the rectangle whose top row is vp.y.
  glViewport(vp.x, height_ - vp.y - vp.height, vp.width, vp.height);
  glClear(GL_COLOR_BUFFER_BIT);
  glBegin(GL_TRIANGLES);
  for (const ClipTri& t : tris)
    for (const ClipVertex& v : t.v) {
      glColor4ub(GLubyte(v.r), GLubyte(v.g), GLubyte(v.b), 255);  // input colours: RGB8 integers
      glVertex4f(v.x, v.y, v.z, v.w);
    }
  glEnd();
  std::vector<uint32_t> gl_rows(buffer_.size());
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error while drawing");
  std::vector<uint32_t> rows(gl_rows.size());  // GL rows run bottom first: flip
  for (int r = 0; r < height_; ++r)
    std::copy_n(gl_rows.data() + size_t(height_ - 1 - r) * width_, width_, rows.data() + size_t(r) * width_);
  return rows;
}

}  // namespace rastsim::mesa
