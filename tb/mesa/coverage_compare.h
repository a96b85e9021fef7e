// SPDX-License-Identifier: Apache-2.0
// Coverage of the same triangles by the reference model and by llvmpipe, compared per
// (triangle, pixel) pair.
//
// - Reference side: the whole reference pipeline (render_scene: primitive assembly,
//   setup with snapping, tiled traversal, interpolation), each triangle of a pass drawn
//   in a constant colour that is its index, so every fragment names its triangle.
// - llvmpipe side: OsMesaRenderer::coverage_masks (one OR-ed bit per triangle).
// - Both give a 32-bit mask per pixel for up to 32 triangles; any differing bit is a
//   mismatch naming the triangle, the pixel and both answers.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "osmesa_renderer.h"
#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim::mesa {

// The vertices of tris[index] as the reference model takes them: exact Q64 positions,
// z = 0.5, constant colour (index + 1, 0, 0) so that every fragment names its triangle.
std::array<SceneVertex, 3> scene_vertices(const GridTri& t, size_t index);
// One triangle list of up to 32 such triangles.
Scene indexed_scene(const std::vector<GridTri>& tris);

// Per pixel (row-major, fb_width x fb_height), bit i set when the reference model emits
// a fragment of tris[i] there (tris.size() <= 32). Throws std::logic_error if a
// triangle emits the same pixel twice or a fragment's colour is not a triangle index.
std::vector<uint32_t> reference_masks(const std::vector<GridTri>& tris, const RasterState& st);

struct Mismatch {
  size_t tri = 0;        // index in the scene
  int x = 0, y = 0;      // pixel
  bool reference = false, llvmpipe = false;  // covered?
};

struct CompareStats {
  uint64_t triangles = 0;
  uint64_t passes = 0;         // batches of <= 32 triangles
  uint64_t decisions = 0;      // (triangle, pixel) pairs compared: triangles * fb pixels
  uint64_t covered = 0;        // pairs the reference covers
  uint64_t mismatches = 0;     // pairs where the two disagree
  uint64_t ties = 0;           // pairs whose pixel centre lies exactly on an edge (the
                               // fill rule decides them), from tie_pixels
  CompareStats& operator+=(const CompareStats& o);
};

// Pixels of a width x height framebuffer whose centre lies on an edge of the closed
// triangle (as given, before any snapping): the (triangle, pixel) pairs the fill rule
// decides. Exact integer arithmetic, independent of both renderers. 0 for zero area.
uint64_t tie_pixels(const GridTri& t, int width, int height);

// Draws `tris` through both, 32 at a time; appends up to `max_report` mismatches.
CompareStats compare_coverage(const std::vector<GridTri>& tris, const RasterState& st, OsMesaRenderer& gl,
                              std::vector<Mismatch>& report, size_t max_report);

// "triangle #i (x0, y0) (x1, y1) (x2, y2): pixel (x, y): rastsim covers, llvmpipe does not".
std::string describe(const Mismatch& m, const std::vector<GridTri>& tris);

}  // namespace rastsim::mesa
