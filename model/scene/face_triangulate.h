// SPDX-License-Identifier: Apache-2.0
// Triangulation of an OBJ polygon face (docs/trace-format.md, "Polygon faces").
//
// - On screen: the face's corners as snapped raw coordinates (raster.coord_format units,
//   |x|, |y| < 2^31, so every orientation product is below 2^65 and exact in i128).
//   A weakly convex simple outline keeps the fan from its first corner (0, k, k + 1); a
//   simple concave one is ear-clipped; both give triangles in the outline's winding.
// - In the face's own plane: whether the 3D polygon crosses itself, independent of the
//   view (so a mesh seen edge-on never fails), in the file's double precision; and, for
//   the perspective camera, its triangles.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace rastsim {

using ScreenPoint = std::array<int64_t, 2>;  // snapped raw x, y (2^-F px)
using FaceTriangle = std::array<uint32_t, 3>;  // corner indices, in the face's winding

enum class OutlineShape {
  Convex,     // weakly convex and simple (collinear corners allowed): fanned
  Collinear,  // every corner on one line (the face seen edge-on): fanned, draws nothing
  Concave,    // simple but not convex: ear-clipped
  Crossing,   // edges cross, touch or fold back, or two corners coincide
};

struct FaceTriangulation {
  OutlineShape shape = OutlineShape::Convex;
  std::vector<FaceTriangle> triangles;  // empty for Crossing
};

// The triangles of a screen outline of n >= 3 corners: n - 2 of them unless Crossing.
FaceTriangulation triangulate_outline(const std::vector<ScreenPoint>& p);

// The fan from the first corner, (0, k, k + 1) for k = 1 .. n - 2.
std::vector<FaceTriangle> fan_triangles(size_t n);

// The first two edges (edge k runs from corner k to corner k + 1 mod n) that cross,
// touch or fold back onto each other in the plane of the 3D polygon `p`, or nullopt when
// the polygon is simple there or degenerate (every corner on one line). The plane is the
// coordinate plane most nearly parallel to the face, so it is exact for planar faces.
std::optional<std::pair<size_t, size_t>> face_crossing_in_plane(const std::vector<std::array<double, 3>>& p);

// The triangles of a 3D polygon of n >= 3 corners that does not cross itself, found in
// its own plane (view independent, for clip-space faces, whose screen outline may lie
// partly behind the eye): as triangulate_outline on the plane's coordinates snapped to a
// 2^30-step grid; fanned when every corner is on one line or the grid makes it cross.
std::vector<FaceTriangle> triangulate_in_plane(const std::vector<std::array<double, 3>>& p);

}  // namespace rastsim
