// SPDX-License-Identifier: Apache-2.0
// llvmpipe's 4x multisample coverage through OSMesa, per sample (docs/mesa.md).
//
// - OSMesa's own buffer cannot be multisampled, so the context (compatibility profile,
//   GL 4.5) renders into a framebuffer object: a 4-sample RGBA8 texture
//   (glTexImage2DMultisample), fixed sample locations.
// - An FBO is not flipped (gallium Y_0_BOTTOM orientation): with the default lower-left
//   clip origin the state tracker keeps gallium's top-left rule (bottom_edge_rule = 0),
//   and the viewport (-P/2, -P/2, P, P) makes gallium's row equal ndc_y * P/2 = the
//   scene's y (and x likewise), so llvmpipe's sample positions, given in its row space,
//   are the scene's (y down). Read-back rows are the scene's rows, unflipped.
// - Coverage: as OsMesaRenderer, triangle i of a pass is drawn in colour bit i with
//   glLogicOp(GL_OR), which applies per sample; then a shader copies sample s of every
//   pixel (texelFetch on the sampler2DMS, exact for unorm8) into a one-sample
//   renderbuffer, read back once per sample: per sample, the set of triangles covering
//   it. No resolve, no rounding.
// - resolved_counts() is the other way round, for cross-checking: one triangle in white,
//   glBlitFramebuffer resolve, covered samples k = round(4 v / 255).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "osmesa_renderer.h"

namespace rastsim::mesa {

inline constexpr int kMsaaSamples = 4;  // the only multisample count llvmpipe has

class OsMesaMsaa {
 public:
  // Creates its own OSMesa context and the 4x framebuffer (width x height px). Throws
  // std::runtime_error when OSMesa, the FBO or the sample count is not as required.
  OsMesaMsaa(int width, int height);
  ~OsMesaMsaa();
  OsMesaMsaa(const OsMesaMsaa&) = delete;
  OsMesaMsaa& operator=(const OsMesaMsaa&) = delete;

  // Per sample s (0..3), per pixel (row-major, row 0 at the top): bit i set when
  // tris[i] covers sample s of that pixel (tris.size() <= kMaxTrisPerPass).
  std::array<std::vector<uint32_t>, kMsaaSamples> sample_masks(const std::vector<GridTri>& tris);

  // Covered samples per pixel of one triangle, from the box-filter resolve of the
  // triangle drawn alone in white on black.
  std::vector<uint8_t> resolved_counts(const GridTri& tri);

  // GL_SAMPLE_POSITION of each sample of the 4x framebuffer: (x, y) in [0, 1) from the
  // pixel's corner, in the FBO's (= the scene's) axes.
  std::array<std::array<float, 2>, kMsaaSamples> sample_positions();
  int samples() const { return samples_; }  // GL_SAMPLES of the bound 4x framebuffer

  std::string renderer_name();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void make_current();
  void draw(const std::vector<GridTri>& tris, bool colour_bits);

  int width_, height_;
  int samples_ = 0;
  void* ctx_ = nullptr;            // OSMesaContext (kept opaque: no GL headers here)
  std::vector<uint32_t> window_;   // OSMesa's own (unused) colour buffer
  unsigned ms_tex_ = 0, ms_fbo_ = 0, ss_rb_ = 0, ss_fbo_ = 0, program_ = 0;
  int sample_uniform_ = -1;
};

}  // namespace rastsim::mesa
