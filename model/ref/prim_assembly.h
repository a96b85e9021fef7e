// SPDX-License-Identifier: Apache-2.0
// Primitive assembly: triangle lists, strips and fans into independent triangles.
//
// - List: vertices (3k, 3k+1, 3k+2).
// - Strip: triangle k is (k, k+1, k+2) for even k and (k+1, k, k+2) for odd k, so every
//   triangle of a strip keeps the winding of the first (OpenGL/Direct3D order).
// - Fan: triangle k is (0, k+1, k+2).
#pragma once

#include <array>
#include <cstddef>

#include "ref/scene.h"

namespace rastsim {

// Number of triangles a primitive command makes.
size_t triangle_count(const CmdPrimitives& p);
// Vertices of triangle k of the command.
std::array<SceneVertex, 3> assemble_triangle(const CmdPrimitives& p, size_t k);

}  // namespace rastsim
