// SPDX-License-Identifier: Apache-2.0
// The exact screen geometry of clip-space triangles (see clip_geometry.h).
#include "clip_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rastsim::mesa {
namespace {

// A polygon vertex: x, y, z, w, its colour (linear in clip space: perspective-correct)
// and the clip planes it was made on (bit k: plane k).
struct Homog {
  std::array<double, 4> p;
  std::array<double, 3> c;
  unsigned planes = 0;
};

// The six view-volume planes as signed distances (inside: >= 0).
double plane_distance(const std::array<double, 4>& p, int plane) {
  switch (plane) {
    case 0: return p[3] + p[0];
    case 1: return p[3] - p[0];
    case 2: return p[3] + p[1];
    case 3: return p[3] - p[1];
    case 4: return p[2];
    default: return p[3] - p[2];
  }
}

std::vector<Homog> clip_against(const std::vector<Homog>& in, int plane) {
  std::vector<Homog> out;
  for (size_t i = 0; i < in.size(); ++i) {
    const Homog& a = in[i];
    const Homog& b = in[(i + 1) % in.size()];
    const double da = plane_distance(a.p, plane), db = plane_distance(b.p, plane);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      const double t = da / (da - db);
      // On this plane, and on any plane both ends were made on (the edge lies in it).
      Homog m{{}, {}, (a.planes & b.planes) | 1u << plane};
      for (int k = 0; k < 4; ++k) m.p[k] = a.p[k] + t * (b.p[k] - a.p[k]);
      for (int k = 0; k < 3; ++k) m.c[k] = a.c[k] + t * (b.c[k] - a.c[k]);
      out.push_back(m);
    }
  }
  return out;
}

// Twice the signed area of (o, a, b).
double cross(const ScreenPoint& o, const ScreenPoint& a, const ScreenPoint& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

VisiblePolygon::VisiblePolygon(const ClipTri& t, const ViewRect& vp) {
  std::vector<Homog> poly;
  for (const ClipVertex& v : t.v)
    poly.push_back({{double(v.x), double(v.y), double(v.z), double(v.w)}, {double(v.r), double(v.g), double(v.b)}, 0});
  // Near, far, left, right, top, bottom: the order of docs/clip-space.md, so the polygon
  // starts at the vertex the reference's does and is fanned alike.
  for (int plane : {4, 5, 0, 1, 2, 3})
    if (!poly.empty()) poly = clip_against(poly, plane);
  const double hw = vp.width / 2.0, hh = vp.height / 2.0;
  std::vector<unsigned> planes;
  for (const Homog& h : poly)  // w > 0 after clipping, but for the eye itself (0, 0, 0, 0)
    if (h.p[3] > 0) {
      pts_.push_back({vp.x + hw + h.p[0] / h.p[3] * hw, vp.y + hh + h.p[1] / h.p[3] * hh});
      inv_w_.push_back(1 / h.p[3]);
      colour_.push_back(h.c);
      planes.push_back(h.planes);
    }
  double area2 = 0;
  for (size_t i = 0; i < pts_.size(); ++i) {
    const size_t j = (i + 1) % pts_.size();
    const ScreenPoint& a = pts_[i];
    const ScreenPoint& b = pts_[j];
    // An edge whose ends were both made on a plane lies in it: bits 0..3 are x and y
    // (the viewport border), 4 and 5 near and far.
    const unsigned common = planes[i] & planes[j];
    const EdgeKind kind = common & 0x30u ? EdgeKind::NearFar : common ? EdgeKind::Border : EdgeKind::Triangle;
    Edge e{a, b.x - a.x, b.y - a.y, 0, 0, 0, kind};
    e.len2 = e.dx * e.dx + e.dy * e.dy;
    if (e.len2 > 0) e.nx = -e.dy / std::sqrt(e.len2), e.ny = e.dx / std::sqrt(e.len2);
    edges_.push_back(e);
    area2 += a.x * b.y - a.y * b.x;
  }
  has_area_ = area2 != 0;
}

double VisiblePolygon::segment_distance(const Edge& e, double px, double py) const {
  const double u = e.len2 > 0 ? std::clamp(((px - e.a.x) * e.dx + (py - e.a.y) * e.dy) / e.len2, 0.0, 1.0) : 0.0;
  return std::hypot(px - (e.a.x + u * e.dx), py - (e.a.y + u * e.dy));
}

double VisiblePolygon::edge_distance(double px, double py) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Edge& e : edges_) best = std::min(best, segment_distance(e, px, py));
  return best;
}

std::optional<EdgeKind> VisiblePolygon::near_edge(double px, double py, double r) const {
  std::optional<EdgeKind> kind;
  double best = r;
  for (const Edge& e : edges_) {
    // A segment is no nearer than its line (a zero-length edge has no line: measure it).
    if (e.len2 > 0 && std::abs((px - e.a.x) * e.nx + (py - e.a.y) * e.ny) > best) continue;
    const double d = segment_distance(e, px, py);
    if (d <= best) best = d, kind = e.kind;
  }
  return kind;
}

bool VisiblePolygon::inside(double px, double py) const {
  if (!has_area_) return false;
  bool pos = false, neg = false;
  for (const Edge& e : edges_) {
    const double c = e.dx * (py - e.a.y) - e.dy * (px - e.a.x);
    pos |= c > 0, neg |= c < 0;
  }
  return !(pos && neg);
}

std::array<double, 3> VisiblePolygon::snapped_colour(double px, double py, double lsb) const {
  std::array<double, 3> rgb{};
  if (pts_.size() < 3) return rgb;
  const auto bary = [&](const std::array<ScreenPoint, 3>& v) {  // screen-space weights of (px, py)
    const double area2 = cross(v[0], v[1], v[2]);
    return std::array<double, 3>{cross({px, py}, v[1], v[2]) / area2, cross(v[0], {px, py}, v[2]) / area2,
                                 cross(v[0], v[1], {px, py}) / area2};
  };
  // The fan triangle (P0, Pi, Pi+1) holding the point best (largest smallest weight).
  size_t best = 1;
  double best_min = -std::numeric_limits<double>::infinity();
  for (size_t i = 1; i + 1 < pts_.size(); ++i) {
    const std::array<double, 3> l = bary({pts_[0], pts_[i], pts_[i + 1]});
    const double m = std::min({l[0], l[1], l[2]});
    if (m > best_min) best_min = m, best = i;
  }
  const std::array<size_t, 3> idx = {0, best, best + 1};
  std::array<ScreenPoint, 3> snapped;
  for (int k = 0; k < 3; ++k)
    snapped[k] = {std::nearbyint(pts_[idx[k]].x / lsb) * lsb, std::nearbyint(pts_[idx[k]].y / lsb) * lsb};
  const std::array<double, 3> l = bary(snapped);
  double den = 0;
  for (int k = 0; k < 3; ++k) den += l[k] * inv_w_[idx[k]];
  for (int k = 0; k < 3; ++k)
    for (int ch = 0; ch < 3; ++ch) rgb[ch] += l[k] * inv_w_[idx[k]] * colour_[idx[k]][ch] / den;
  return rgb;
}

std::array<double, 3> exact_colour(const ClipTri& t, const ViewRect& vp, double sx, double sy) {
  const double hw = vp.width / 2.0, hh = vp.height / 2.0;
  const double nx = (sx - (vp.x + hw)) / hw, ny = (sy - (vp.y + hh)) / hh;
  std::array<double, 3> a, c;
  for (int i = 0; i < 3; ++i) {
    a[i] = double(t.v[i].x) - nx * double(t.v[i].w);
    c[i] = double(t.v[i].y) - ny * double(t.v[i].w);
  }
  // b is orthogonal to a and c: b = (a x c) / sum(a x c).
  const std::array<double, 3> b = {a[1] * c[2] - a[2] * c[1], a[2] * c[0] - a[0] * c[2], a[0] * c[1] - a[1] * c[0]};
  const double sum = b[0] + b[1] + b[2];
  std::array<double, 3> rgb{};
  for (int i = 0; i < 3; ++i) {
    const double wi = b[i] / sum;
    rgb[0] += wi * t.v[i].r, rgb[1] += wi * t.v[i].g, rgb[2] += wi * t.v[i].b;
  }
  return rgb;
}

}  // namespace rastsim::mesa
