// SPDX-License-Identifier: Apache-2.0
// 2D-homogeneous rasterization (clip.method = "homogeneous", Olano and Greer 1997;
// docs/clip-space.md, "Homogeneous rasterization"): a clip-space triangle drawn from its
// homogeneous vertices, with no clipping, no divide by w and no new vertices.
//
// - Vertex: mapped to the viewport in homogeneous form, x~ = x (W/2) + (X + W/2 - ox) w,
//   y~ = y (H/2) + (Y + H/2 - oy) w (ox, oy: the snapping origin, pixels), z 2^s, w; the
//   four rounded to nearest even into a block format of their own (HomogeneousVertex):
//   signed integers |V| <= 2^30 sharing one exponent. They depend on the vertex alone,
//   so the two triangles of a shared edge build the same edge function.
// - Edges: the 2x2 minors of two vertices' (x~, y~, w), i.e. the rows of the adjugate of
//   the triangle's 3x3 matrix, as functions of the raw sample position: exact integers.
//   Oriented by the sign of the determinant, the interior is E >= 0 at all three edges
//   (the top-left rule, ref/tri_setup.h fill_bias, on ties); a sample inside all three
//   has w > 0, so nothing behind the eye is drawn (Olano and Greer's sign rule).
// - Near and far: per-sample tests 0 <= z/w <= 1, with z/w = sum E_k Z_k / sum E_k W_k.
// - Traversal: tiles of raster.tile_size over a region (below), each rejected, accepted
//   or tested sample by sample, as the tiled walk does.
// - Attributes: the edge values are proportional to the perspective-correct barycentrics;
//   depth is z/w, linear on screen.
// Widths, roundings and the region in docs/clip-space.md.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "ref/coarse_raster.h"
#include "ref/front_end.h"
#include "ref/interpolate.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "ref/tri_setup.h"

namespace rastsim {

inline constexpr int kHomogeneousBits = 30;  // |x~|, |y~|, |z|, |w| <= 2^30 in a vertex's block

// A vertex's x~, y~, z~ = z 2^s, w = v[i] 2^exp.
struct HomogeneousVertex {
  std::array<int64_t, 4> v{};
  int exp = 0;
};
// s: the smallest with 2^s >= max(W/2, H/2, 1) of the viewport map, at most 31 - F
// (F = raster.coord_format's fraction bits), so that 2^(F+s) det fits the datapath.
int homogeneous_depth_shift(const ViewportMap& m, int frac_bits);
HomogeneousVertex homogeneous_vertex(const ClipVertex& c, const ViewportMap& m, int64_t origin_x, int64_t origin_y,
                                     int depth_shift);

// f(x, y) = a x + b y + c of a raw sample position (units 2^-F relative to the origin);
// it passes when f + bias >= 0.
struct SampleFunc {
  i128 a = 0, b = 0, c = 0;
  int bias = 0;
  i128 eval(int64_t x, int64_t y) const { return a * x + b * y + c; }
};

struct HomogeneousTriangle {
  std::array<SampleFunc, 3> edge;  // edge m: vertices m, m+1 (vertex k's weight is edge (k+1)%3)
  SampleFunc near_test, far_test;  // n = sum E_k Z_k >= 0; depth_den - n >= 0
  i128 depth_den = 1;              // 2^(F+s) det > 0: z/w = n / depth_den
  std::array<int64_t, 3> w{};      // W_k (affine weights E_k W_k)
  std::array<int, 3> weight_shift{};  // exp_max - exp_k: perspective weights E_k 2^shift
  bool ccw_on_screen = false;
  PixelRect region;                // pixels traversed
  uint32_t depth_lo = 0, depth_hi = 0;  // depth_range N, F in raster.depth_bits unorm
  std::array<std::array<uint8_t, 3>, 3> rgb{};
  std::array<int32_t, 3> tex_s{}, tex_t{};
  int64_t tex_min = 0, tex_max = 0;
  bool perspective = true;
  RecipMethod recip = RecipMethod::Exact;
  int recip_seed_bits = 8, recip_iterations = 2;
  int frac_bits = 8, samples = 1, depth_bits = 24;
  AaMode aa_mode = AaMode::Msaa;
  int64_t origin_x = 0, origin_y = 0;

  int64_t sample_x(int px) const { return ((int64_t(px) - origin_x) << frac_bits) + (int64_t{1} << (frac_bits - 1)); }
  int64_t sample_y(int py) const { return ((int64_t(py) - origin_y) << frac_bits) + (int64_t{1} << (frac_bits - 1)); }
  // The sample at raw (x, y) passes the three edges, near and far.
  bool covers(int64_t x, int64_t y) const;
};

// Sets up one clip-space triangle (Accepted, CulledZeroArea: determinant 0, the facing
// culls, CulledOutsideClip: an empty region). Throws SceneError naming `loc` for a texture
// coordinate outside interp.texcoord_format.
SetupOutcome setup_homogeneous(const std::array<ClipVertex, 3>& v, const ClipState& clip, const RasterState& st,
                               const SourceLoc& loc, HomogeneousTriangle& t);

// The fragment of pixel (px, py) with attributes at raw sample position (x, y).
Fragment homogeneous_fragment(const HomogeneousTriangle& t, int px, int py, int64_t x, int64_t y);

// Traverses and shades one set-up triangle (one fragment a covered pixel; ssaa: a covered
// sample), counting the walk into c (tiles, sample tests, fragments).
void rasterize_homogeneous(const HomogeneousTriangle& t, int tile_size, TraversalCounters& c,
                           const std::function<void(const Fragment&)>& emit);

// True when `p` is drawn by draw_homogeneous: a clip-space triangle command (List, Strip,
// Fan) under clip.method = homogeneous. Points and lines take the clip method.
bool draws_homogeneous(const CmdPrimitives& p, const RasterState& st);

// Every triangle of such a command, in order: culled behind the eye (w <= 0 at every
// vertex) or outside one plane of the view volume (counted into fe as the clip method
// counts them), else set up, its outcome passed to `setup_done` (true: rasterize), and
// rasterized into `emit`. Throws SceneError naming `loc` as front_end and setup do.
void draw_homogeneous(const CmdPrimitives& p, const RasterState& st, const SourceLoc& loc, FrontEndStats& fe,
                      TraversalCounters& c, const std::function<bool(SetupOutcome)>& setup_done,
                      const std::function<void(const Fragment&)>& emit);

}  // namespace rastsim
