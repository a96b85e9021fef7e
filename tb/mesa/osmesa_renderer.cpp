// SPDX-License-Identifier: Apache-2.0
// llvmpipe through OSMesa: context, D3D11-like state, OR-mask coverage passes.
#include "osmesa_renderer.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace rastsim::mesa {
namespace {

using ClipControlFn = void (*)(GLenum origin, GLenum depth);

}  // namespace

void* create_llvmpipe_context() {
  // One rasterizer thread: deterministic and fair on a shared 2-core machine; llvmpipe's
  // coverage does not depend on the thread count (bins are independent).
  setenv("LP_NUM_THREADS", "1", 0);
  // OSMesa is gallium-based; insist on llvmpipe rather than softpipe.
  setenv("GALLIUM_DRIVER", "llvmpipe", 0);
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!ctx) throw std::runtime_error("OSMesaCreateContextAttribs failed");
  return ctx;
}

void set_coverage_state(bool multisample) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_DITHER);
  glDisable(GL_BLEND);
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glDisable(GL_SAMPLE_COVERAGE);
  if (multisample) glEnable(GL_MULTISAMPLE);
  else glDisable(GL_MULTISAMPLE);
  glShadeModel(GL_FLAT);
  glLogicOp(GL_OR);
  glClearColor(0, 0, 0, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

void draw_triangles(const std::vector<GridTri>& tris, bool colour_bits) {
  glBegin(GL_TRIANGLES);
  for (size_t i = 0; i < tris.size(); ++i) {
    // Bit i of the RGBA8 pixel (R holds bits 0..7, A bits 24..31); OR keeps them all.
    const uint32_t bit = colour_bits ? uint32_t{1} << i : ~uint32_t{0};
    glColor4ub(GLubyte(bit), GLubyte(bit >> 8), GLubyte(bit >> 16), GLubyte(bit >> 24));
    // raw (2^-F px) -> NDC: ndc = raw * 2 / (2^F * P), a power of two (2^-20 for F = 8,
    // P = 8192), so the product is exact.
    const float scale = 2.0f / (float(int64_t{1} << tris[i].frac_bits) * float(kViewport));
    for (int v = 0; v < 3; ++v) {
      const float x = float(tris[i].x[v]), y = float(tris[i].y[v]);
      if (int64_t(x) != tris[i].x[v] || int64_t(y) != tris[i].y[v])
        throw std::invalid_argument("vertex not exact in binary32");
      glVertex3f(x * scale, y * scale, 0.0f);
    }
  }
  glEnd();
}

OsMesaRenderer::OsMesaRenderer(int width, int height)
    : width_(width), height_(height), buffer_(size_t(width) * size_t(height)) {
  OSMesaContext ctx = static_cast<OSMesaContext>(create_llvmpipe_context());
  ctx_ = ctx;
  if (!OSMesaMakeCurrent(ctx, buffer_.data(), GL_UNSIGNED_BYTE, width, height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  auto clip_control = reinterpret_cast<ClipControlFn>(OSMesaGetProcAddress("glClipControl"));
  if (!clip_control) throw std::runtime_error("glClipControl not available (GL 4.5 / ARB_clip_control)");
  // Upper-left origin: window y grows downwards (D3D); zero-to-one depth (D3D's range,
  // so z = 0 needs no depth clipping arithmetic).
  clip_control(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  // The OSMesa colour buffer is a window-system buffer, which gallium stores top row
  // first (Y_0_TOP): the state tracker flips y (row = H - y_gl) and, with GL_UPPER_LEFT,
  // selects gallium's top-left edge rule (bottom_edge_rule = 0) in that row space. The
  // viewport below makes gallium's row coordinate equal to ndc_y * P/2 exactly:
  // row = ndc_y * P/2 + (H - vy - P/2) with vy = H - P/2; likewise x = ndc_x * P/2.
  glViewport(-kViewport / 2, height - kViewport / 2, kViewport, kViewport);
  set_coverage_state(false);
  glEnable(GL_COLOR_LOGIC_OP);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error during set-up");
}

OsMesaRenderer::~OsMesaRenderer() { OSMesaDestroyContext(static_cast<OSMesaContext>(ctx_)); }

std::string OsMesaRenderer::renderer_name() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}
std::string OsMesaRenderer::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

std::vector<uint32_t> OsMesaRenderer::coverage_masks(const std::vector<GridTri>& tris) {
  if (tris.size() > size_t(kMaxTrisPerPass)) throw std::invalid_argument("more than 32 triangles in one pass");
  // A process may hold an OsMesaMsaa context too: make this one current.
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx_), buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  glClear(GL_COLOR_BUFFER_BIT);
  draw_triangles(tris, true);
  std::vector<uint32_t> gl_rows(size_t(width_) * size_t(height_));
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("OpenGL error while drawing");
  // glReadPixels returns GL rows (bottom first), the reverse of gallium's rows: flip.
  std::vector<uint32_t> masks(gl_rows.size());
  for (int r = 0; r < height_; ++r)
    std::copy_n(gl_rows.data() + size_t(height_ - 1 - r) * width_, width_, masks.data() + size_t(r) * width_);
  return masks;
}

}  // namespace rastsim::mesa
