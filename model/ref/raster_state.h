// SPDX-License-Identifier: Apache-2.0
// RasterState: the fixed-function state every raster stage reads, built once from the
// config (config/raster_state_config.h) and updated by scene commands (viewport, scissor, clears).
#pragma once

#include <cstdint>
#include <vector>

#include "ref/bin_params.h"
#include "ref/fixed_point.h"
#include "ref/2d/line_raster.h"
#include "ref/2d/polygon_fill.h"
#include "ref/texture/texture.h"

namespace rastsim {

enum class FillRule { TopLeft, BottomRight, Inclusive, Exclusive };
enum class CullMode { None, Back, Front };
enum class DepthFunc { Never, Less, LEqual, Equal, Greater, GEqual, NotEqual, Always };
enum class OutOfRange { Error, Cull };
// raster.traversal (ref/traverse.h, docs/traversal.md).
enum class Traversal { Tiled, Bbox, Hierarchical, Scanline };
// Attribute interpolation (interp.method): plane equations, an exact rational a pixel
// (the default), or the notes' incremental span DDA (ref/interpolate.h).
enum class InterpMethod { Plane, Dda };
enum class InterpArith { F32, Fixed };  // interp.dda_arith
// raster.aa_mode (docs/antialiasing.md): with raster.samples > 1, shade once a pixel at its
// centre and write that colour to every covered sample (msaa), or shade every covered
// sample at its own position (ssaa).
enum class AaMode { Msaa, Ssaa };
// clip.method (docs/clip-space.md): Sutherland-Hodgman clipping before the divide by w,
// or 2D-homogeneous rasterization (Olano and Greer 1997).
enum class ClipMethod { Clip, Homogeneous };
// interp.recip: the per-pixel reciprocal of perspective-correct interpolation, exact
// (the golden) or a seed table and Newton-Raphson steps in fixed point.
enum class RecipMethod { Exact, Newton };

// Half-open pixel rectangle [x0, x1) x [y0, y1).
// depth.hiz: no bound table, the farthest depth of a block, or its nearest and farthest.
enum class HizMode { Off, Max, MinMax };
// depth.hiz_sync: how the timed levels keep the table in step with the ROP (the
// reference's table is zero-lag either way): an exact interlock (a tile is tested once
// nothing in flight touches its blocks), or a table that lags the ROP (no wait; culls
// from stale bounds, accepts only on idle blocks: docs/depth-culling.md "Lagged").
enum class HizSync { Interlock, Lagged };

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  int64_t area() const { return empty() ? 0 : int64_t(x1 - x0) * (y1 - y0); }
  PixelRect intersect(const PixelRect& o) const;
  bool operator==(const PixelRect&) const = default;
};

// Every value comes from the config (raster_state_from_config) or a scene command; the
// initialisers below are neutral, not defaults.
struct RasterState {
  // Architecture (from the config).
  FixedFormat coord_format;
  int tile_size = 0;  // px
  FillRule fill_rule = FillRule::TopLeft;
  CullMode cull = CullMode::None;
  bool front_ccw = false;  // true: a triangle that appears counter-clockwise on screen is front
  DepthFunc depth_func = DepthFunc::Always;
  int depth_bits = 0;
  bool depth_write = false;
  // depth.early: the depth test before interpolation's colour and texture work where the
  // state allows it (docs/depth.md); the image is the same either way.
  bool depth_early = false;
  // depth.hiz, depth.hiz_block (px), depth.hiz_bytes: hierarchical Z (ref/hiz.h,
  // docs/depth-culling.md); the image is the same either way.
  HizMode hiz_mode = HizMode::Off;
  int hiz_block = 0;
  int64_t hiz_bytes = 0;
  uint64_t hiz_base = 0;  // depth.hiz_base: byte address of the spilled table in DRAM
  HizSync hiz_sync = HizSync::Interlock;  // depth.hiz_sync (SystemC and RTL only)
  OutOfRange out_of_range = OutOfRange::Error;
  int fb_width = 0, fb_height = 0;  // framebuffer (display) size, px
  // 2D primitives (config keys line.*, polygon.*).
  LineMethod line_method = LineMethod::Diamond;  // first enumerator: neutral
  DdaArith dda_arith = DdaArith::F32;
  PolygonRule polygon_rule = PolygonRule::EvenOdd;
  // Triangle traversal (keys raster.traversal, raster.hier_levels, raster.scanline_arith).
  Traversal traversal = Traversal::Tiled;
  std::vector<int> hier_levels;  // px, strictly decreasing powers of two
  DdaArith scanline_arith = DdaArith::F32;
  // Attribute interpolation (config keys interp.method, interp.dda_arith, interp.dda_frac_bits).
  InterpMethod interp_method = InterpMethod::Plane;
  InterpArith interp_arith = InterpArith::Fixed;
  int interp_frac_bits = 16;  // fraction bits of the fixed-point DDA accumulator
  // Multisampling (raster.samples, raster.aa_mode; ref/sample_pattern.h). 1: today's
  // single sample at the pixel centre.
  int samples = 1;
  AaMode aa_mode = AaMode::Msaa;
  // Geometry front end and perspective-correct attributes (keys clip.*, interp.perspective,
  // interp.recip*, interp.texcoord_format; docs/clip-space.md).
  ClipMethod clip_method = ClipMethod::Clip;
  float guard_band = 1.0f;  // clip.guard_band: x/y clipped only outside +-g w
  bool perspective = false;  // interp.perspective: a/w and 1/w planes and a reciprocal a pixel
  RecipMethod recip = RecipMethod::Exact;
  int recip_seed_bits = 0;      // interp.recip_seed_bits: index bits of the seed table
  int recip_iterations = 0;     // interp.recip_iterations: Newton-Raphson steps
  FixedFormat texcoord_format;  // interp.texcoord_format: s, t out of interpolation
  int color_frac_bits = 0;      // interp.color_frac_bits: vertex colour unsigned 8.F into setup (0: RGB8)
  BinParams bin;               // pipeline.mode, bin.*: the binned pipeline (docs/binning.md)
  TextureParams texture;        // texture.*: texel format, layout, base address, cache (docs/texture.md)

  // Scene state (from commands).
  int viewport_width = 0, viewport_height = 0;
  bool scissor_enabled = false;
  PixelRect scissor;

  // Snapping origin: the viewport centre's pixel corner, rounded down.
  int64_t origin_x() const { return viewport_width / 2; }
  int64_t origin_y() const { return viewport_height / 2; }
  // Pixels a primitive may touch: the viewport, clipped to the framebuffer and scissor.
  PixelRect clip_rect() const;
};

const char* to_string(DepthFunc f);

}  // namespace rastsim
