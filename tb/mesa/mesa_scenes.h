// SPDX-License-Identifier: Apache-2.0
// Seeded random triangle scenes for the llvmpipe comparison, every vertex on the
// 1/256 px grid (8 sub-pixel bits) so neither rasterizer has to round (docs/mesa.md).
//
// - Tiny: extents up to 3 px, many of them covering no pixel centre at all.
// - Sliver: long (16..600 px) and a few 1/256 px wide, some exactly collinear.
// - Large: vertices up to 64, 256 or 3000 px outside the framebuffer on every side.
// - Mesh: jittered grids, each quad split along a random diagonal (shared edges, so
//   top-left ties between neighbours on pixel centres).
// - Fan: triangles around one centre, spokes often through pixel centres and along
//   the axes (horizontal and vertical shared edges).
// Each vertex coordinate is put on pixel centres, pixel corners, half pixels or any
// 1/256 grid point (a per-scene or per-vertex choice), so ties are common.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "osmesa_renderer.h"

namespace rastsim::mesa {

enum class SceneKind { Tiny, Sliver, Large, Mesh, Fan };
const char* to_string(SceneKind k);

// About `approx_tris` triangles of one kind inside (or, for Large, around) a
// width x height framebuffer; the same seed gives the same scene.
std::vector<GridTri> make_scene(SceneKind kind, uint64_t seed, int approx_tris, int width, int height);

// "(x0, y0) (x1, y1) (x2, y2)" in pixels, exact decimals (raw / 2^frac_bits).
std::string describe(const GridTri& t);

// The same triangles with `extra_bits` more fraction bits, every coordinate moved by
// an offset in [-1/2, +1/2] of an 8-bit LSB (endpoints included: exact ties), the same
// offset for equal coordinates so shared vertices stay shared. Probes snapping.
std::vector<GridTri> off_grid(const std::vector<GridTri>& tris, int extra_bits, uint64_t seed);

// The same triangles rounded to the 1/256 grid (frac_bits 8) on the test side, ties up
// (+inf) or to even, written out independently of the model's fixed_point.cpp.
std::vector<GridTri> snap_to_grid(const std::vector<GridTri>& tris, bool ties_to_even);

}  // namespace rastsim::mesa
