// SPDX-License-Identifier: Apache-2.0
// Recognises the vertex shaders whose clip-space position rastsim import-apitrace can
// compute on the CPU: gl_Position = M1 * M2 * ... * Mk * vec4(position, 1.0), each Mi a
// `uniform mat4`, position an `attribute vec3` (or `in vec3`), either written in place or
// through one local `vec4 p = vec4(position, 1.0);` that is never assigned again.
// Anything else (a position computed from other terms, gl_Position written twice or
// under a condition, a matrix that is not a uniform) is refused with the reason; nothing
// is guessed (docs/workloads.md, "Importing an apitrace capture").
#pragma once

#include <string>
#include <vector>

namespace rastsim::apitrace {

struct ShaderForm {
  bool ok = false;
  std::string reason;                   // why not, when !ok
  std::vector<std::string> matrices;    // M1 ... Mk, in the order they multiply
  std::string position;                 // the vec3 attribute
  std::vector<std::string> attributes;  // every attribute the shader declares
};

ShaderForm recognise_vertex_shader(const std::string& source);

}  // namespace rastsim::apitrace
