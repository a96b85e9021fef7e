// SPDX-License-Identifier: Apache-2.0
// llvmpipe through OSMesa drawing clip-space triangles, set up as the project's clip-space
// convention asks (docs/clip-space.md): glVertex4f positions, per-vertex glColor,
// glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE), a real glViewport for `viewport_xform`.
//
// - One off-screen RGBA8 colour buffer (no depth, stencil or accumulation buffer),
//   its own context (a process may hold the screen-space ones too).
// - Identity matrices (positions pass through as clip coordinates); depth clamp off (so
//   near and far clip); culling, depth test, dither, blending, logic op and
//   multisampling off; smooth shading, which OpenGL makes perspective-correct.
// - `viewport_xform X Y W H` (y down from the top-left) is glViewport(X, fb_h - Y - H, W,
//   H): with the upper-left origin, NDC y = -1 lands on row Y (checked by the hand-worked
//   tests of test_mesa_clip.cpp, which fix the orientation).
// - Read-back rows are flipped so that row 0 is the top row (as the screen-space
//   renderer's, osmesa_renderer.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "clip_scenes.h"

namespace rastsim::mesa {

class OsMesaClipRenderer {
 public:
  // Throws std::runtime_error when OSMesa fails or has no glClipControl.
  OsMesaClipRenderer(int width, int height);
  ~OsMesaClipRenderer();
  OsMesaClipRenderer(const OsMesaClipRenderer&) = delete;
  OsMesaClipRenderer& operator=(const OsMesaClipRenderer&) = delete;

  // tris drawn in order with glBegin(GL_TRIANGLES) into a cleared buffer: per pixel
  // (row-major, row 0 at the top) R | G << 8 | B << 16 | A << 24, A = 255 where a
  // triangle covers the pixel and 0 elsewhere.
  std::vector<uint32_t> render(const std::vector<ClipTri>& tris, const ViewRect& vp);

  std::string renderer_name() const;  // GL_RENDERER
  std::string version() const;        // GL_VERSION
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void make_current();
  int width_, height_;
  void* ctx_ = nullptr;           // OSMesaContext (opaque: no GL headers here)
  std::vector<uint32_t> buffer_;  // the colour buffer OSMesa renders into, RGBA8
};

}  // namespace rastsim::mesa
