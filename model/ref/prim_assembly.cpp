// SPDX-License-Identifier: Apache-2.0
#include "ref/prim_assembly.h"

namespace rastsim {

size_t triangle_count(const CmdPrimitives& p) {
  const size_t n = p.vertices.size();
  switch (p.topology) {
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

std::array<SceneVertex, 3> assemble_triangle(const CmdPrimitives& p, size_t k) {
  const auto& v = p.vertices;
  switch (p.topology) {
    case Topology::List: return {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
    case Topology::Strip:
      if (k % 2 == 0) return {v[k], v[k + 1], v[k + 2]};
      return {v[k + 1], v[k], v[k + 2]};
    case Topology::Fan: return {v[0], v[k + 1], v[k + 2]};
    case Topology::Points:
    case Topology::Lines:
    case Topology::LineStrip:
    case Topology::LineLoop: break;
  }
  return {};
}

}  // namespace rastsim
