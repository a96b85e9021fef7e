// SPDX-License-Identifier: Apache-2.0
// The reciprocal precision study (`rastsim recip-grid`, docs/clip-space.md "Reciprocal
// precision"): a scene rendered with interp.recip = "newton" at every seed table width
// and Newton-Raphson step count, each fragment's colour and texture coordinate against
// the render with interp.recip = "exact".
//
// - The fragment streams of the two renders are compared in order, value by value: the
//   reciprocal changes no coverage (depth, which decides it, is affine), so the i-th
//   fragment of both is the same sample; a stream that differs in length or position is
//   an error (it would mean the reciprocal reached coverage).
// - Errors are |newton - exact| in LSBs of the attribute: colour r, g, b in RGB8 units,
//   texture coordinates s, t in LSBs of interp.texcoord_format (2^-F repeats). Every
//   fragment counts, those of affine triangles (equal 1/w: no reciprocal) too.
#pragma once

#include <cstdint>
#include <vector>

#include "ref/raster_state.h"
#include "ref/scene.h"

namespace rastsim {

// One attribute class's error against exact over a render.
struct AttributeError {
  uint64_t values = 0;  // values compared (fragments x attributes of the class)
  uint64_t wrong = 0;   // of them different from exact
  uint64_t max = 0;     // largest |newton - exact|, LSBs
  uint64_t sum = 0;     // summed |newton - exact|, LSBs
  double mean() const { return values ? double(sum) / double(values) : 0.0; }
  bool exact() const { return wrong == 0; }
};

struct RecipGridRow {
  int seed_bits = 0, iterations = 0;  // interp.recip_seed_bits, interp.recip_iterations
  AttributeError colour, texcoord;    // r, g, b; s, t
  bool exact() const { return colour.exact() && texcoord.exact(); }
};

struct RecipGrid {
  uint64_t fragments = 0;  // of the exact render (each row compares these)
  std::vector<RecipGridRow> rows;  // by iterations, then seed bits, both ascending
};

// Renders `scene` with `arch` under interp.recip = exact and then newton for seed bits
// 1..max_seed_bits x iterations 0..max_iterations (interp.perspective as `arch` has it).
// Throws SceneError when a render fails, or when a newton render's fragment positions
// differ from exact's.
RecipGrid recip_grid(const Scene& scene, const RasterState& arch, int max_seed_bits = 16, int max_iterations = 4);

}  // namespace rastsim
