// SPDX-License-Identifier: Apache-2.0
// Triangulation of an OBJ polygon face (face_triangulate.h). The same segment tests run
// on snapped integers (wide type i128: exact) and on the face's plane in doubles (wide
// type long double).
#include "scene/face_triangulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "ref/fixed_point.h"

namespace rastsim {

namespace {

template <class W, class P>
W orient(const P& a, const P& b, const P& c) {
  return (W(b[0]) - W(a[0])) * (W(c[1]) - W(a[1])) - (W(b[1]) - W(a[1])) * (W(c[0]) - W(a[0]));
}

template <class W>
int sign(W v) {
  return (v > W(0)) - (v < W(0));
}

// q, known to be on the line through a and b, lies on the closed segment ab.
template <class P>
bool within(const P& a, const P& b, const P& q) {
  return std::min(a[0], b[0]) <= q[0] && q[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= q[1] &&
         q[1] <= std::max(a[1], b[1]);
}

// The closed segments ab and cd have a point in common.
template <class W, class P>
bool segments_meet(const P& a, const P& b, const P& c, const P& d) {
  const int o1 = sign(orient<W>(a, b, c)), o2 = sign(orient<W>(a, b, d));
  const int o3 = sign(orient<W>(c, d, a)), o4 = sign(orient<W>(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
         (o4 == 0 && within(c, d, b));
}

// The first pair of edges that meet other than at the corner two neighbours share: a
// zero-length edge, neighbours folding back along one line, or any point shared by two
// edges that are not neighbours. O(n^2): faces are small.
template <class W, class P>
std::optional<std::pair<size_t, size_t>> first_crossing(const std::vector<P>& p) {
  const size_t n = p.size();
  auto at = [&](size_t i) -> const P& { return p[i % n]; };
  for (size_t i = 0; i < n; ++i) {
    const P &a = at(i), &b = at(i + 1), &c = at(i + 2);
    if (a == b) return std::pair{i, i};
    const W dot = (W(a[0]) - W(b[0])) * (W(c[0]) - W(b[0])) + (W(a[1]) - W(b[1])) * (W(c[1]) - W(b[1]));
    if (sign(orient<W>(a, b, c)) == 0 && dot > W(0)) return std::pair{i, (i + 1) % n};
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through corner 0
      if (segments_meet<W>(at(i), at(i + 1), at(j), at(j + 1))) return std::pair{i, j};
    }
  return std::nullopt;
}

// Every corner on one line (or all at one point).
template <class W, class P>
bool all_collinear(const std::vector<P>& p) {
  size_t k = 1;
  while (k < p.size() && p[k] == p[0]) ++k;
  for (size_t i = k + 1; i < p.size(); ++i)
    if (sign(orient<W>(p[0], p[k], p[i])) != 0) return false;
  return true;
}

// Twice the signed area (shoelace), exact for |coordinates| < 2^31 and n < 2^60.
i128 area2(const std::vector<ScreenPoint>& p) {
  i128 a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const ScreenPoint &u = p[i], &v = p[(i + 1) % p.size()];
    a += i128(u[0]) * v[1] - i128(v[0]) * u[1];
  }
  return a;
}

// No turn against the outline's orientation s (a straight corner is fine).
bool weakly_convex(const std::vector<ScreenPoint>& p, int s) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    if (sign(orient<i128>(p[i], p[(i + 1) % n], p[(i + 2) % n])) == -s) return false;
  return true;
}

// Ear clipping of a simple outline of orientation s (+1 or -1). An ear is a corner b
// turning with s whose triangle (a, b, c) holds no other remaining corner, on its
// boundary included (every corner is tested: O(n^3) at worst, faces are small). Every
// simple polygon of more than three corners has an ear (Meisters' two ears theorem), and
// cutting one leaves a simple polygon, so the loop ends with n - 2 triangles.
std::vector<FaceTriangle> ear_clip(const std::vector<ScreenPoint>& p, int s) {
  std::vector<uint32_t> ring(p.size());
  std::iota(ring.begin(), ring.end(), 0u);
  auto turn = [&](uint32_t a, uint32_t b, uint32_t c) { return sign(orient<i128>(p[a], p[b], p[c])) * s; };
  auto is_ear = [&](size_t k) {
    const size_t m = ring.size();
    const uint32_t a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
    if (turn(a, b, c) <= 0) return false;
    for (size_t j = 0; j < m; ++j) {
      const uint32_t q = ring[j];
      if (q == a || q == b || q == c) continue;
      if (turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0) return false;
    }
    return true;
  };
  std::vector<FaceTriangle> out;
  size_t k = 0, misses = 0;
  while (ring.size() > 3) {
    const size_t m = ring.size();
    if (is_ear(k)) {
      out.push_back({ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]});
      ring.erase(ring.begin() + std::ptrdiff_t(k));
      k = (k + m - 2) % (m - 1);  // back to the cut ear's left neighbour, which may be an ear now
      misses = 0;
    } else {
      k = (k + 1) % m;
      if (++misses > m) throw std::logic_error("ear clipping found no ear in a simple polygon");
    }
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

}  // namespace

std::vector<FaceTriangle> fan_triangles(size_t n) {
  std::vector<FaceTriangle> out;
  for (uint32_t k = 1; k + 1 < n; ++k) out.push_back({0, k, k + 1});
  return out;
}

FaceTriangulation triangulate_outline(const std::vector<ScreenPoint>& p) {
  if (p.size() == 3) return {OutlineShape::Convex, fan_triangles(3)};
  if (all_collinear<i128>(p)) return {OutlineShape::Collinear, fan_triangles(p.size())};
  if (first_crossing<i128>(p)) return {OutlineShape::Crossing, {}};
  const int s = sign(area2(p));  // a simple polygon has a non-zero area
  if (weakly_convex(p, s)) return {OutlineShape::Convex, fan_triangles(p.size())};
  return {OutlineShape::Concave, ear_clip(p, s)};
}

namespace {

// The polygon in its own plane: the coordinate plane most nearly parallel to it (the
// axis the largest fan-triangle normal is most nearly along dropped), an affine map of a
// planar face that keeps crossings, convexity and ears; nullopt when every corner is on
// one line (no plane).
std::optional<std::vector<std::array<double, 2>>> plane_coords(const std::vector<std::array<double, 3>>& p) {
  using Vec = std::array<double, 3>;
  Vec normal{};
  double best = 0;
  for (size_t k = 1; k + 1 < p.size(); ++k) {
    const Vec u{p[k][0] - p[0][0], p[k][1] - p[0][1], p[k][2] - p[0][2]};
    const Vec v{p[k + 1][0] - p[0][0], p[k + 1][1] - p[0][1], p[k + 1][2] - p[0][2]};
    const Vec c{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]);
    if (len > best) best = len, normal = c;
  }
  if (best == 0) return std::nullopt;
  size_t drop = 0;
  for (size_t a = 1; a < 3; ++a)
    if (std::abs(normal[a]) > std::abs(normal[drop])) drop = a;
  std::vector<std::array<double, 2>> q;
  for (const Vec& v : p) q.push_back({v[drop == 0 ? 1 : 0], v[drop == 2 ? 1 : 2]});
  return q;
}

}  // namespace

std::optional<std::pair<size_t, size_t>> face_crossing_in_plane(const std::vector<std::array<double, 3>>& p) {
  const auto q = plane_coords(p);
  if (!q) return std::nullopt;
  return first_crossing<long double>(*q);
}

std::vector<FaceTriangle> triangulate_in_plane(const std::vector<std::array<double, 3>>& p) {
  if (p.size() == 3) return fan_triangles(3);
  const auto q = plane_coords(p);
  if (!q) return fan_triangles(p.size());  // every corner on one line: no area to cover
  // Onto an integer grid of kPlaneGridSteps across the face's larger extent (the same
  // scale on both axes), where triangulate_outline's tests are exact.
  constexpr double kPlaneGridSteps = double(int64_t{1} << 30);
  std::array<double, 2> lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (const auto& c : *q)
    for (size_t a = 0; a < 2; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  const double span = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  std::vector<ScreenPoint> grid;
  for (const auto& c : *q)
    grid.push_back({std::llround((c[0] - lo[0]) / span * kPlaneGridSteps),
                    std::llround((c[1] - lo[1]) / span * kPlaneGridSteps)});
  FaceTriangulation t = triangulate_outline(grid);
  // Corners closer than a grid step to an edge may cross on the grid although the face
  // does not: fanned, a sliver that thin at most.
  if (t.shape == OutlineShape::Crossing) return fan_triangles(p.size());
  return std::move(t.triangles);
}

}  // namespace rastsim
