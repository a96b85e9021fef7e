// SPDX-License-Identifier: Apache-2.0
// llvmpipe (Mesa's LLVM software rasterizer) through OSMesa, set up like Direct3D 11,
// as an independent coverage oracle for the reference model (docs/mesa.md).
//
// - One off-screen RGBA8 colour buffer (no depth, stencil or accumulation buffer).
// - glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE): on OSMesa's window-system buffer this
//   selects gallium's top-left rule in its top-down row space (osmesa_renderer.cpp).
// - Exact coordinates: identity matrices and a power-of-two viewport P x P placed at
//   (-P/2, H - P/2), so that gallium's row = ndc_y * P/2 = scene y and likewise for x
//   (ndc = 2 * pixel / P); every step is a power-of-two scale, exact in binary32 for
//   points on the 2^-F grid with |coordinate| * 2^F < 2^24.
// - Read-back rows are flipped so that row 0 is the scene's top row.
// - Coverage masks: up to 32 triangles per pass, triangle i drawn in colour bit i with
//   glLogicOp(GL_OR), so one read-back gives, per pixel, the set of triangles that
//   cover it, whatever their overlaps.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rastsim::mesa {

inline constexpr int kSubpixelBits = 8;      // sub-pixel bits (D3D11, llvmpipe FIXED_ORDER)

// A triangle's vertices in raw units of 2^-frac_bits px from the framebuffer's top-left
// corner (x right, y down). frac_bits = 8 is the grid both rasterizers snap to (no
// rounding); 9 or 10 puts vertices between grid points to probe the snapping itself.
struct GridTri {
  std::array<int64_t, 3> x{}, y{};
  int frac_bits = kSubpixelBits;  // 8..12
};
inline constexpr int kMaxTrisPerPass = 32;   // bits in one RGBA8 pixel
// Viewport side (px), a power of two so that pixel <-> NDC is an exact scale by 2/P.
// 8192 keeps vertices up to +-4096 px inside the clip volume (no clipping, so no new
// vertices), far inside llvmpipe's 16384 viewport limit.
inline constexpr int kViewport = 8192;

// A new llvmpipe OSMesa context (compatibility profile, RGBA, no depth, stencil or
// accumulation buffer), as an opaque OSMesaContext. Sets LP_NUM_THREADS=1 and
// GALLIUM_DRIVER=llvmpipe unless the environment sets them. Throws std::runtime_error.
void* create_llvmpipe_context();

// The current context's state for coverage passes: identity matrices; culling, depth
// test, dither, blending and alpha-to-coverage off; flat shading; logic op OR (not
// enabled); clear colour 0; multisampling on or off.
void set_coverage_state(bool multisample);

// Draws tris with glBegin(GL_TRIANGLES) in the current context, raw 2^-F px -> NDC by
// the exact scale 2 / (2^F P): triangle i in colour bit i (colour_bits) or in white.
// Throws std::invalid_argument for a vertex that is not exact in binary32.
void draw_triangles(const std::vector<GridTri>& tris, bool colour_bits);

class OsMesaRenderer {
 public:
  // Creates the context and buffer (width x height px). Sets LP_NUM_THREADS=1 unless
  // the environment already sets it. Throws std::runtime_error when OSMesa fails.
  OsMesaRenderer(int width, int height);
  ~OsMesaRenderer();
  OsMesaRenderer(const OsMesaRenderer&) = delete;
  OsMesaRenderer& operator=(const OsMesaRenderer&) = delete;

  // Per pixel (row-major, row 0 at the top), bit i set when tris[i] covers it
  // (tris.size() <= kMaxTrisPerPass).
  std::vector<uint32_t> coverage_masks(const std::vector<GridTri>& tris);

  std::string renderer_name() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;        // GL_VERSION
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  void* ctx_ = nullptr;             // OSMesaContext (kept opaque: no GL headers here)
  std::vector<uint32_t> buffer_;    // the colour buffer OSMesa renders into, RGBA8
};

}  // namespace rastsim::mesa
