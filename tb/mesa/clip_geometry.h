// SPDX-License-Identifier: Apache-2.0
// The exact geometry of a clip-space triangle on screen, in double, independent of both
// renderers: the oracle that says which pixel centres lie within one coordinate LSB of
// an edge (where the two may differ) and what the perspective-correct colour is.
//
// - Visible part: Sutherland-Hodgman in double against the six planes of the view volume
//   (-w <= x, y <= w, 0 <= z <= w), then x/w, y/w mapped by the viewport transform. Its
//   edges are the triangle's own edges (straight on screen where w > 0), the near and
//   far lines (z/w is linear on screen) and the viewport border (never within half a
//   pixel of a pixel centre).
// - Colour: the clip-space barycentrics b of the point that projects to the pixel centre
//   (sum b_i (x_i - nx w_i) = 0, sum b_i (y_i - ny w_i) = 0, sum b_i = 1), which is what
//   perspective-correct interpolation computes, from the binary32 inputs read exactly.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "clip_scenes.h"

namespace rastsim::mesa {

struct ScreenPoint {
  double x = 0, y = 0;  // pixels, y down
};

// Where an edge of the visible polygon comes from: the triangle's own edge, the near or
// far plane (z = 0, z = w), or the border of the viewport (x, y = +-w).
enum class EdgeKind { Triangle, NearFar, Border };
inline constexpr int kEdgeKinds = 3;

// The visible part of t, projected: a convex polygon (empty when nothing is visible; it
// may be degenerate, e.g. a collinear triangle's segment or a single point).
class VisiblePolygon {
 public:
  VisiblePolygon(const ClipTri& t, const ViewRect& vp);
  const std::vector<ScreenPoint>& vertices() const { return pts_; }
  bool empty() const { return pts_.empty(); }
  // Distance (px) from (px, py) to the nearest edge (segments); infinity when empty.
  double edge_distance(double px, double py) const;
  // The kind of the nearest edge when edge_distance(px, py) <= r, cheaply (a segment is
  // measured only when its line is near); nothing when every edge is farther.
  std::optional<EdgeKind> near_edge(double px, double py, double r) const;
  // True when (px, py) lies inside (either winding, edges included; false for a polygon of
  // zero area). Meaningful away from the edges, where rounding cannot change the answer.
  bool inside(double px, double py) const;
  // The perspective-correct colour at (px, py) once the polygon's screen vertices are
  // snapped to the lsb grid (round to nearest): the colour of the fan triangle (P0, Pi,
  // Pi+1) that holds the point, as the reference fans and snaps it. Where it differs from
  // exact_colour, the colour depends on sub-LSB vertex positions (slivers, steep
  // gradients), which the two renderers treat differently (llvmpipe interpolates over
  // its unsnapped float positions).
  std::array<double, 3> snapped_colour(double px, double py, double lsb) const;

 private:
  struct Edge {
    ScreenPoint a;
    double dx = 0, dy = 0, len2 = 0;  // b - a and its squared length
    double nx = 0, ny = 0;            // unit normal (0 for a zero-length edge)
    EdgeKind kind = EdgeKind::Triangle;
  };
  double segment_distance(const Edge& e, double px, double py) const;
  std::vector<ScreenPoint> pts_;
  std::vector<double> inv_w_;                  // 1/w of each vertex
  std::vector<std::array<double, 3>> colour_;  // RGB of each vertex (unrounded)
  std::vector<Edge> edges_;
  bool has_area_ = false;
};

// Perspective-correct colour (R, G, B in 0..255, unrounded) at screen point (sx, sy).
std::array<double, 3> exact_colour(const ClipTri& t, const ViewRect& vp, double sx, double sy);

}  // namespace rastsim::mesa
