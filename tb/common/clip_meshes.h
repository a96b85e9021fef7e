// SPDX-License-Identifier: Apache-2.0
// Closed clip-space meshes around a perspective camera (a cube and a UV sphere) and the
// coverage count of a render: the watertightness scenes of both clip methods (tb/test_front_end.cpp,
// tb/test_homogeneous.cpp). Seen from inside, every pixel is covered exactly once; some
// faces are cut by the near plane and some lie behind the eye.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "ref/pipeline.h"
#include "ref/scene.h"

namespace rastsim::testing_common {

// Times each sample of each pixel was written: (py * W + px) * S + sample.
struct Coverage {
  std::vector<int> count;
  RenderStats stats;
};

inline Coverage render_coverage(const std::vector<CmdPrimitives>& prims, const RasterState& st) {
  Scene scene;
  for (const auto& p : prims) scene.commands.push_back(Command{p, SourceLoc{"test", 1}});
  Coverage c;
  c.count.assign(size_t(st.fb_width) * size_t(st.fb_height) * size_t(st.samples), 0);
  render_scene(scene, st, c.stats, [&](const Fragment& f) {
    for (int s = 0; s < f.samples; ++s)
      if (f.mask >> s & 1) ++c.count[(size_t(f.y) * size_t(st.fb_width) + size_t(f.x)) * size_t(f.samples) + size_t(s)];
  });
  return c;
}

// The samples not covered exactly once.
inline size_t samples_not_covered_once(const Coverage& c) {
  return size_t(std::count_if(c.count.begin(), c.count.end(), [](int n) { return n != 1; }));
}

// Eye space (x right, y up, looking down -z) to Vulkan clip space: x_c = f x, y_c = -f y
// (NDC y = -1 is the top row), z_c = far / (near - far) z + near far / (near - far),
// w_c = -z (z_c = 0 at z = -near and z_c = w_c at z = -far), f = 1 / tan(fov / 2).
struct Perspective {
  double f, a, b;
  Perspective(double fov_deg, double near, double far)
      : f(1 / std::tan(fov_deg * M_PI / 360)), a(far / (near - far)), b(near * far / (near - far)) {}
  ClipVertex operator()(double x, double y, double z) const {
    ClipVertex v;
    v.x = float(f * x);
    v.y = float(-f * y);
    v.z = float(a * z + b);
    v.w = float(-z);
    v.r = v.g = v.b = 255;
    return v;
  }
};

// An eye-space point of the mesh: a fixed rotation and offset of the model point (the
// same model point always gives the same clip-space vertex, bit for bit).
inline ClipVertex place(const Perspective& P, double x, double y, double z) {
  const double c1 = std::cos(0.7), s1 = std::sin(0.7), c2 = std::cos(0.4), s2 = std::sin(0.4);
  const double x1 = c1 * x - s1 * z, z1 = s1 * x + c1 * z;  // about y
  const double y2 = c2 * y - s2 * z1, z2 = s2 * y + c2 * z1;  // about x
  return P(x1 + 0.21, y2 - 0.13, z2 + 0.17);
}

// A cube of half-size 1 around the eye, each face an n x n grid of two-triangle quads.
inline CmdPrimitives cube_mesh(const Perspective& P, int n) {
  CmdPrimitives m;
  m.topology = Topology::List;
  const auto pt = [&](int face, int i, int j) {
    const double u = 2.0 * i / n - 1, v = 2.0 * j / n - 1, s = face % 2 ? 1.0 : -1.0;
    switch (face / 2) {
      case 0: return place(P, s, u, v);
      case 1: return place(P, u, s, v);
      default: return place(P, u, v, s);
    }
  };
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (auto [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
          m.clip_vertices.push_back(pt(face, i + a, j + b));
  return m;
}

// A UV sphere of radius 1 around the eye: rings x segments quads, the poles' triangles
// degenerate (zero area, culled by setup).
inline CmdPrimitives sphere_mesh(const Perspective& P, int rings, int segments) {
  CmdPrimitives m;
  m.topology = Topology::List;
  const auto pt = [&](int r, int s) {
    if (r == 0 || r == rings) return place(P, 0, r == 0 ? 1 : -1, 0);
    const double th = M_PI * r / rings, ph = 2 * M_PI * (s % segments) / segments;
    return place(P, std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      for (auto [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        m.clip_vertices.push_back(pt(r + a, s + b));
  return m;
}

}  // namespace rastsim::testing_common
