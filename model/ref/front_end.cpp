// SPDX-License-Identifier: Apache-2.0
// Compiled with -ffp-contract=off (model/ref/CMakeLists.txt): every binary32 product and
// sum below rounds on its own, as docs/clip-space.md states; a fused multiply-add would
// change the snapped vertices.
#include "ref/front_end.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ref/prim_assembly.h"

namespace rastsim {

ViewportMap viewport_map(const ClipState& clip, const RasterState& st) {
  const ViewportXform& v = clip.xform;
  const int X = v.whole_viewport ? 0 : v.x, Y = v.whole_viewport ? 0 : v.y;
  const int W = v.whole_viewport ? st.viewport_width : v.width, H = v.whole_viewport ? st.viewport_height : v.height;
  ViewportMap m;
  m.half_w = float(W) / 2.0f;
  m.centre_x = float(X) + m.half_w;
  m.half_h = float(H) / 2.0f;
  m.centre_y = float(Y) + m.half_h;
  m.depth_scale = clip.depth_far - clip.depth_near;
  m.depth_near = clip.depth_near;
  m.depth_lo = std::min(clip.depth_near, clip.depth_far);
  m.depth_hi = std::max(clip.depth_near, clip.depth_far);
  return m;
}

uint32_t round_colour(float c, int color_frac_bits) {
  const float scaled = std::ldexp(c, color_frac_bits);  // exact: a power-of-two scale of a value <= 255
  return uint32_t(std::clamp(std::nearbyint(scaled), 0.0f, std::ldexp(255.0f, color_frac_bits)));
}

bool to_screen(const ClipVertex& v, const ViewportMap& m, int color_frac_bits, SceneVertex& out) {
  if (!(v.w > 0.0f)) return false;
  const float q = 1.0f / v.w;
  const float xw = (v.x * q) * m.half_w + m.centre_x;
  const float yw = (v.y * q) * m.half_h + m.centre_y;
  const float zw = (v.z * q) * m.depth_scale + m.depth_near;
  if (!std::isfinite(q) || !std::isfinite(xw) || !std::isfinite(yw) || !std::isfinite(zw)) return false;
  out.x = Q64::from_double(double(xw));
  out.y = Q64::from_double(double(yw));
  out.z = double(std::clamp(zw, m.depth_lo, m.depth_hi));
  const float rgb[3] = {v.r, v.g, v.b};
  for (size_t c = 0; c < 3; ++c) {
    const uint32_t q = round_colour(rgb[c], color_frac_bits);  // unsigned 8.F
    (c == 0 ? out.r : c == 1 ? out.g : out.b) = uint8_t(q >> color_frac_bits);
    out.rgb_frac[c] = uint16_t(q & ((1u << color_frac_bits) - 1));
  }
  out.inv_w = q;
  out.s = v.s;
  out.t = v.t;
  return true;
}

float plane_distance(const ClipVertex& v, ClipPlane p, float guard_band) {
  switch (p) {
    case ClipPlane::Near: return v.z;
    case ClipPlane::Far: return v.w - v.z;
    case ClipPlane::Left: return v.x + guard_band * v.w;
    case ClipPlane::Right: return guard_band * v.w - v.x;
    case ClipPlane::Top: return v.y + guard_band * v.w;
    case ClipPlane::Bottom: return guard_band * v.w - v.y;
  }
  return 0.0f;
}

ClipVertex clip_intersection(const ClipVertex& inside, const ClipVertex& outside, ClipPlane p, float guard_band) {
  const float d_in = plane_distance(inside, p, guard_band), d_out = plane_distance(outside, p, guard_band);
  // From the end nearer the plane (the inside one on a tie): t <= 1/2, and a + t (b - a)
  // keeps that end's digits, where from the far end the sum would cancel them (a vertex
  // with w near 0: the new w lost a tenth of its value from the inside end). Which end
  // depends only on the edge's two vertices, so both triangles of a shared edge make
  // the same vertex bit for bit.
  const bool from_in = d_in <= -d_out;  // d_in >= 0 > d_out
  const ClipVertex& a = from_in ? inside : outside;
  const ClipVertex& b = from_in ? outside : inside;
  const float d_a = from_in ? d_in : d_out, d_b = from_in ? d_out : d_in;
  const float t = d_a / (d_a - d_b);  // in [0, 1/2]
  const auto lerp = [t](float u, float v) { return u + t * (v - u); };
  ClipVertex o;
  o.x = lerp(a.x, b.x);
  o.y = lerp(a.y, b.y);
  o.z = lerp(a.z, b.z);
  o.w = lerp(a.w, b.w);
  // Colour in binary32 too; it is rounded once, to unsigned 8.F, by to_screen.
  o.r = lerp(a.r, b.r);
  o.g = lerp(a.g, b.g);
  o.b = lerp(a.b, b.b);
  o.s = lerp(a.s, b.s);
  o.t = lerp(a.t, b.t);
  // Exactly on the plane (its distance is 0), whatever the rounding above did.
  const float gw = guard_band * o.w;
  switch (p) {
    case ClipPlane::Near: o.z = 0.0f; break;
    case ClipPlane::Far: o.z = o.w; break;
    case ClipPlane::Left: o.x = -gw; break;
    case ClipPlane::Right: o.x = gw; break;
    case ClipPlane::Top: o.y = -gw; break;
    case ClipPlane::Bottom: o.y = gw; break;
  }
  return o;
}

std::vector<ClipVertex> clip_triangle(const std::array<ClipVertex, 3>& tri, float guard_band, FrontEndStats& stats,
                                      bool& clipped) {
  std::vector<ClipVertex> poly(tri.begin(), tri.end()), next;
  clipped = false;
  for (ClipPlane p : kClipPlanes) {
    const bool all_inside = std::all_of(poly.begin(), poly.end(),
                                        [&](const ClipVertex& v) { return plane_distance(v, p, guard_band) >= 0.0f; });
    if (all_inside) continue;  // the plane leaves the polygon as it is
    clipped = true;
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const ClipVertex& cur = poly[i];
      const ClipVertex& nxt = poly[(i + 1) % poly.size()];
      const bool cur_in = plane_distance(cur, p, guard_band) >= 0.0f;
      const bool nxt_in = plane_distance(nxt, p, guard_band) >= 0.0f;
      if (cur_in) next.push_back(cur);
      if (cur_in == nxt_in) continue;
      next.push_back(cur_in ? clip_intersection(cur, nxt, p, guard_band) : clip_intersection(nxt, cur, p, guard_band));
      ++stats.clip_vertices_made;
    }
    poly.swap(next);
    if (poly.size() < 3) return {};
  }
  return poly;
}

namespace {

bool inside_volume(const ClipVertex& v, float guard_band) {
  return v.w > 0.0f && std::all_of(kClipPlanes.begin(), kClipPlanes.end(),
                                   [&](ClipPlane p) { return plane_distance(v, p, guard_band) >= 0.0f; });
}

// One front-end invocation: the command's state and where its triangles go.
struct FrontEnd {
  const ViewportMap map;
  const int color_frac_bits;  // interp.color_frac_bits
  const float guard_band;
  const bool front_ccw;
  const ClipState& clip;
  FrontEndStats& stats;
  const ScreenTriangleSink& emit;

  void out(const ScreenTriangle& t) {
    ++stats.clip_triangles_out;
    emit(t);
  }

  void triangle(const std::array<ClipVertex, 3>& v) {
    ++stats.clip_triangles_in;
    if (std::all_of(v.begin(), v.end(), [](const ClipVertex& c) { return c.w <= 0.0f; })) {
      ++stats.triangles_behind;
      return;
    }
    for (ClipPlane p : kClipPlanes)
      if (std::all_of(v.begin(), v.end(), [&](const ClipVertex& c) { return plane_distance(c, p, guard_band) < 0.0f; })) {
        ++stats.triangles_culled_outside;
        return;
      }
    bool clipped = false;
    const std::vector<ClipVertex> poly = clip_triangle(v, guard_band, stats, clipped);
    if (clipped) ++stats.triangles_clipped;
    if (poly.empty()) {
      ++stats.triangles_culled_outside;
      return;
    }
    std::vector<SceneVertex> s(poly.size());
    for (size_t i = 0; i < poly.size(); ++i)
      if (!to_screen(poly[i], map, color_frac_bits, s[i])) {
        ++stats.triangles_nonfinite;
        return;
      }
    for (size_t i = 1; i + 1 < s.size(); ++i) out({s[0], s[i], s[i + 1]});  // a fan from the first vertex
  }

  // Quad a0 a1 b1 b0 (a parallelogram, corners in order around it) as two triangles
  // (a0, a1, b1), (a0, b1, b0), both front-facing so that raster.cull = back keeps them.
  void quad(SceneVertex a0, SceneVertex a1, SceneVertex b1, SceneVertex b0) {
    const double area2 = (a1.x.to_double() - a0.x.to_double()) * (b1.y.to_double() - a0.y.to_double()) -
                         (a1.y.to_double() - a0.y.to_double()) * (b1.x.to_double() - a0.x.to_double());
    const bool cw = area2 > 0;  // y down: > 0 is clockwise on screen (tri_setup.cpp)
    if (cw == front_ccw) std::swap(a1, b0);  // the same corners, the other way round
    out({a0, a1, b1});
    out({a0, b1, b0});
  }

  void point(const ClipVertex& v) {
    ++stats.points_in;
    SceneVertex c;
    if (!inside_volume(v, guard_band) || !to_screen(v, map, color_frac_bits, c)) {
      ++stats.points_culled;
      return;
    }
    const float h = clip.point_size / 2.0f, cx = float(c.x.to_double()), cy = float(c.y.to_double());
    const auto corner = [&](float dx, float dy, float s, float t) {
      SceneVertex k = c;
      k.x = Q64::from_double(double(cx + dx));
      k.y = Q64::from_double(double(cy + dy));
      if (clip.point_sprite) {
        k.s = s;
        k.t = t;
      }
      return k;
    };
    quad(corner(-h, -h, 0, 0), corner(h, -h, 1, 0), corner(h, h, 1, 1), corner(-h, h, 0, 1));
  }

  void line(ClipVertex a, ClipVertex b) {
    ++stats.lines_in;
    bool clipped = false;
    for (ClipPlane p : kClipPlanes) {
      const bool a_in = plane_distance(a, p, guard_band) >= 0.0f, b_in = plane_distance(b, p, guard_band) >= 0.0f;
      if (!a_in && !b_in) {
        ++stats.lines_culled;
        return;
      }
      if (a_in == b_in) continue;
      clipped = true;
      ++stats.clip_vertices_made;
      if (a_in) b = clip_intersection(a, b, p, guard_band);
      else a = clip_intersection(b, a, p, guard_band);
    }
    SceneVertex sa, sb;
    if (!to_screen(a, map, color_frac_bits, sa) || !to_screen(b, map, color_frac_bits, sb)) {
      ++stats.lines_culled;
      return;
    }
    if (clipped) ++stats.lines_clipped;
    // x-major (|dx| >= |dy|): widened by half a pixel up and down; y-major: left and right.
    const float ax = float(sa.x.to_double()), ay = float(sa.y.to_double());
    const float bx = float(sb.x.to_double()), by = float(sb.y.to_double());
    const bool x_major = std::fabs(bx - ax) >= std::fabs(by - ay);
    const float ox = x_major ? 0.0f : 0.5f, oy = x_major ? 0.5f : 0.0f;
    const auto moved = [](SceneVertex v, float x, float y) {
      v.x = Q64::from_double(double(x));
      v.y = Q64::from_double(double(y));
      return v;
    };
    quad(moved(sa, ax - ox, ay - oy), moved(sb, bx - ox, by - oy), moved(sb, bx + ox, by + oy),
         moved(sa, ax + ox, ay + oy));
  }
};

// clip.guard_band where the viewport_xform rectangle covers the viewport, whose box
// setup bounds pixels by; else 1: x and y clipped at the rectangle's own edges.
float guard_band_of(const ViewportXform& x, const RasterState& st) {
  const bool covers = x.whole_viewport || (x.x <= 0 && x.y <= 0 && int64_t(x.x) + x.width >= st.viewport_width &&
                                           int64_t(x.y) + x.height >= st.viewport_height);
  return covers ? st.guard_band : 1.0f;
}

}  // namespace

void check_clip_space_finite(const CmdPrimitives& p, const SourceLoc& loc) {
  for (size_t i = 0; i < p.clip_vertices.size(); ++i) {
    const ClipVertex& v = p.clip_vertices[i];
    for (float f : {v.x, v.y, v.z, v.w, v.s, v.t})
      if (!std::isfinite(f))
        throw SceneError(loc.str() + ": clip-space vertex " + std::to_string(i) +
                         " has a value that is not a finite binary32 (x y z w s t must be within +-3.4e38)");
  }
}

void front_end(const CmdPrimitives& p, const RasterState& st, const SourceLoc& loc, FrontEndStats& stats,
               const ScreenTriangleSink& emit) {
  if (st.clip_method == ClipMethod::Homogeneous && triangle_count(p.topology, 3) > 0)
    throw SceneError(loc.str() + ": clip.method = homogeneous is modelled at the reference level only (rastsim "
                                 "render); the other levels draw clip-space triangles with clip.method = \"clip\" "
                                 "(docs/clip-space.md, \"Levels\")");
  check_clip_space_finite(p, loc);
  FrontEnd fe{viewport_map(p.clip, st), st.color_frac_bits, guard_band_of(p.clip.xform, st), st.front_ccw, p.clip, stats, emit};
  const auto& v = p.clip_vertices;
  const size_t n = v.size();
  switch (p.topology) {
    case Topology::List:
    case Topology::Strip:
    case Topology::Fan:
      for (size_t k = 0; k < triangle_count(p.topology, n); ++k) {
        const auto i = triangle_indices(p.topology, k);
        fe.triangle({v[i[0]], v[i[1]], v[i[2]]});
      }
      break;
    case Topology::Points:
      for (const ClipVertex& c : v) fe.point(c);
      break;
    case Topology::Lines:
      for (size_t i = 0; i + 1 < n; i += 2) fe.line(v[i], v[i + 1]);
      break;
    case Topology::LineStrip:
    case Topology::LineLoop:
      for (size_t i = 0; i + 1 < n; ++i) fe.line(v[i], v[i + 1]);
      if (p.topology == Topology::LineLoop && n >= 2) fe.line(v[n - 1], v[0]);
      break;
  }
}

}  // namespace rastsim
