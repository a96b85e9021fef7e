// SPDX-License-Identifier: Apache-2.0
// Triangle setup: snap, orient, cull, edge equations, bounding box, attributes.
//
// - Snaps the three vertices to raster.coord_format, relative to the viewport centre,
//   with round-to-nearest-even (fixed_point.h: snap_coord).
// - Signed doubled area from the snapped vertices (exact); zero area is culled, and per
//   raster.cull back- or front-facing triangles.
// - Three edge equations E(x, y) = A*x + B*y + C in raw units, oriented so that the
//   interior is E > 0 for either winding, with the fill-rule bias folded in so that a
//   sample is covered exactly when E + bias >= 0 (bias is 0 or -1).
// - Bounding box of the snapped vertices in pixels, clamped to viewport and scissor:
//   the pixels whose centre, or with raster.samples > 1 whose sample positions' bounding
//   box, may be covered.
// - Per-vertex attributes (colour unsigned 8.F, F = interp.color_frac_bits; depth quantised to raster.depth_bits, texture
//   coordinates quantised to interp.texcoord_format) and the perspective weights Q_k
//   of the three 1/w (perspective_weights), with the flag `affine` when interpolation
//   needs no reciprocal (docs/clip-space.md, "Perspective-correct interpolation").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "ref/fixed_point.h"
#include "ref/raster_state.h"
#include "ref/sample_pattern.h"
#include "ref/scene.h"

namespace rastsim {

// One edge: E(x, y) = a*x + b*y + c, x and y raw s.I.F coordinates (relative to the
// origin). Widths for s.I.F: a, b need I+F+2 bits; c and E need 2I+2F+3 (fixed-point.md).
struct EdgeEq {
  int64_t a = 0, b = 0;
  i128 c = 0;
  int bias = 0;  // 0 when samples on the edge are covered, -1 when they are not

  // Edge value at raw sample point (x, y), before bias.
  i128 eval(int64_t x, int64_t y) const { return i128(a) * x + i128(b) * y + c; }
  // The same in int64, for a triangle whose edges64 holds and a point in the format's range.
  int64_t eval64(int64_t x, int64_t y) const { return a * x + b * y + static_cast<int64_t>(c); }
};

// Fill-rule bias (0 or -1) of an edge oriented so that the interior is E > 0: a sample on
// the edge is covered when E + bias >= 0 (top_left: a left edge, a > 0, or a top edge,
// a == 0 and b > 0; y grows downward).
int fill_bias(const EdgeEq& e, FillRule rule);

// A texture coordinate (repeats) in raw interp.texcoord_format units, rounded to nearest
// even; nullopt outside the format or not finite.
std::optional<int32_t> quantize_texcoord(float v, const FixedFormat& fmt);

// Smallest pixel index whose centre (p + 1/2, raw units relative to pixel `origin`) is
// >= raw, and the largest whose centre is <= raw: the bounding box's pixel range.
int64_t first_pixel_at_or_after(int64_t raw, int64_t origin, int frac_bits);
int64_t last_pixel_at_or_before(int64_t raw, int64_t origin, int frac_bits);

enum class SetupOutcome {
  Accepted,
  CulledZeroArea,
  CulledBackFace,
  CulledFrontFace,
  CulledOutOfRange,   // raster.out_of_range = cull and a vertex lies outside the format
  CulledOutsideClip,  // bounding box misses the viewport/scissor: nothing to traverse
};
const char* to_string(SetupOutcome o);

struct SetupTriangle {
  std::array<int64_t, 3> x{}, y{};  // snapped raw coordinates, relative to the origin
  std::array<EdgeEq, 3> edge{};     // edge i runs from vertex i to vertex (i+1)%3
  i128 area2 = 0;                   // doubled area, > 0 after orientation (raw^2 units)
  bool ccw_on_screen = false;       // winding as the scene gave it, seen on screen
  PixelRect bbox;                   // pixels whose centres may be covered, clipped
  std::array<uint32_t, 3> z{};      // depth, unorm raster.depth_bits
  // Per-vertex colour r, g, b, unsigned 8.F (F = color_frac_bits: the vertex's r << F |
  // its fraction bits); interpolation rounds the pixel's colour to RGB8 once.
  std::array<std::array<uint32_t, 3>, 3> rgb{};
  int color_frac_bits = 0;                      // interp.color_frac_bits
  std::array<int32_t, 3> tex_s{}, tex_t{};      // texture coordinate, raw interp.texcoord_format
  int64_t tex_min = 0, tex_max = 0;             // that format's raw range (clamps extrapolation)
  // Perspective-correct interpolation: the weights Q_k < 2^24 of the vertices' 1/w
  // (perspective_weights); affine when interp.perspective is false or the three are equal,
  // and then colour and texture coordinates are the affine rational (no reciprocal) and
  // persp_q is {1, 1, 1} (a common scale cancels).
  std::array<uint32_t, 3> persp_q{1, 1, 1};
  bool affine = true;
  RecipMethod recip = RecipMethod::Exact;  // interp.recip and its parameters
  int recip_seed_bits = 8, recip_iterations = 2;
  int64_t origin_x = 0, origin_y = 0;  // pixel of raw (0, 0), to map samples back
  // How interpolation evaluates this triangle's attributes (from the state at setup, so
  // every stage that interpolates, reference or timed, uses the same method).
  InterpMethod interp_method = InterpMethod::Plane;
  InterpArith interp_arith = InterpArith::Fixed;
  int interp_frac_bits = 16;
  int depth_bits = 24;  // raster.depth_bits: the range the dda method clamps depth to
  int samples = 1;      // raster.samples: coverage is a mask of this many bits a pixel
  AaMode aa_mode = AaMode::Msaa;
  // The texture the triangle is drawn with, its command's (none bound: untextured): the
  // timed model's setup sets it for its texture stage (sc/texture.h); the reference's
  // setup leaves it unbound and samples with the command's state.
  TextureState texture;
  // The 64-bit paths (same results as i128, tb/test_int64_paths.cpp): edges64 when every
  // edge value at a point of the format's range fits int64 (fixed_point.h
  // edges_fit_int64); an interpolation numerator w0 a0 + w1 a1 + w2 a2 (a_k < 2^A, A =
  // max(8 + F, raster.depth_bits), F = interp.color_frac_bits) fits int64 when every
  // |w_k| <= w64_limit = floor((2^63 - 1) / (3 M)), M = max(2^A - 1, |s_k|, |t_k|) the
  // largest attribute magnitude of the triangle, checked per sample point (interpolate.cpp).
  bool edges64 = false;
  int64_t w64_limit = 0;

  // Raw coordinate of the centre of pixel column px / row py.
  int64_t sample_x(int px, int frac_bits) const {
    return ((int64_t(px) - origin_x) << frac_bits) + (int64_t{1} << (frac_bits - 1));
  }
  int64_t sample_y(int py, int frac_bits) const {
    return ((int64_t(py) - origin_y) << frac_bits) + (int64_t{1} << (frac_bits - 1));
  }
  uint32_t full_mask() const { return full_sample_mask(samples); }
};

// Perspective weights of three binary32 1/w (finite, > 0) in block floating point: each
// 24-bit significand m_k (hidden bit included) of 1/w_k = m_k 2^(e_k - 23) is shifted to
// the largest exponent E and rounded to nearest even, Q_k = max(1, RNE(m_k 2^(e_k - E))),
// so 1 <= Q_k < 2^24 and the largest is >= 2^23. The common scale 2^(E - 23) cancels in
// sum e_k Q_k a_k / sum e_k Q_k; max(1, .) keeps a weight from vanishing (1/w ratios
// beyond 2^24) so that the denominator is > 0 inside the triangle.
std::array<uint32_t, 3> perspective_weights(const std::array<float, 3>& inv_w);

// Sets up one triangle. On CulledOutOfRange with raster.out_of_range = error it throws
// SceneError naming `loc` and the vertex instead of returning. It throws SceneError too for
// a texture coordinate outside interp.texcoord_format, a 1/w that is not finite and > 0,
// and a triangle with different 1/w under interp.method = dda with interp.perspective
// (the DDA is affine only).
SetupOutcome setup_triangle(const std::array<SceneVertex, 3>& v, const RasterState& st,
                            const SourceLoc& loc, SetupTriangle& out);

}  // namespace rastsim
