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

// Where a vertex shader's varying comes from: `V = A;` or `V = A.SWIZZLE;` with A an
// attribute and SWIZZLE its first components in order (.xy, .st, .rg, .xyz, .rgb, ...),
// assigned once at the top level of main(). Anything else (computed, through a matrix,
// written twice or under a condition) is refused with the reason: the importer cannot
// prove the per-vertex value without running the shader.
struct VaryingSource {
  bool ok = false;
  std::string reason;     // why not, when !ok
  std::string attribute;  // A
  std::string type;       // A's type (vec2, vec3, vec4)
};
VaryingSource varying_source(const std::string& vertex_source, const std::string& varying);

// What a fragment shader does with a texture (docs/workloads.md, "Textures"):
// - Untextured: no texture2D() in it;
// - Replace: gl_FragColor = texture2D(S, V), directly or through one local vec4;
// - Modulate: gl_FragColor = that lookup * C (or C * lookup), C a varying vec4;
// - Other: any other use; `sampler` and `coord` are still given when the shader has
//   exactly one sampler2D uniform and one varying vec2 (else empty, and `reason` says).
// S a `uniform sampler2D`, V a varying vec2 sampled as it arrives.
struct FragmentForm {
  enum class Kind { Untextured, Replace, Modulate, Other };
  Kind kind = Kind::Untextured;
  std::string sampler, coord, colour;  // S, V, C
  std::string reason;                  // Other: why not a plain lookup
};
FragmentForm recognise_fragment_shader(const std::string& source);

}  // namespace rastsim::apitrace
