// SPDX-License-Identifier: Apache-2.0
#include "ref/prim_assembly.h"

namespace rastsim {

size_t triangle_count(Topology t, size_t n) {
  switch (t) {
    case Topology::List: return n / 3;
    case Topology::Strip:
    case Topology::Fan: return n >= 3 ? n - 2 : 0;
    case Topology::Points:  // clip-space only: the front end expands them (docs/clip-space.md)
    case Topology::Lines:
    case Topology::LineStrip:
    case Topology::LineLoop: return 0;
  }
  return 0;
}

std::array<size_t, 3> triangle_indices(Topology t, size_t k) {
  switch (t) {
    case Topology::List: return {3 * k, 3 * k + 1, 3 * k + 2};
    case Topology::Strip:
      if (k % 2 == 0) return {k, k + 1, k + 2};
      return {k + 1, k, k + 2};
    case Topology::Fan: return {0, k + 1, k + 2};
    case Topology::Points:
    case Topology::Lines:
    case Topology::LineStrip:
    case Topology::LineLoop: break;
  }
  return {};
}

size_t triangle_count(const CmdPrimitives& p) { return triangle_count(p.topology, p.vertices.size()); }

std::array<SceneVertex, 3> assemble_triangle(const CmdPrimitives& p, size_t k) {
  const auto i = triangle_indices(p.topology, k);
  return {p.vertices[i[0]], p.vertices[i[1]], p.vertices[i[2]]};
}

void reject_clip_space(const CmdPrimitives& p, const SourceLoc& loc) {
  if (p.clip_space())
    throw SceneError(loc.str() + ": clip-space primitives (tri4, v4) are not modelled at this level yet: render, "
                                 "simulate and estimate draw them (docs/clip-space.md, \"Levels\")");
}

}  // namespace rastsim
