// SPDX-License-Identifier: Apache-2.0
#include "ref/study/recip_grid.h"

#include <cstdlib>
#include <string>

#include "ref/pipeline.h"

namespace rastsim {

namespace {

void add_error(AttributeError& e, int64_t got, int64_t want) {
  const uint64_t d = uint64_t(std::llabs(got - want));
  ++e.values;
  e.wrong += d != 0;
  e.sum += d;
  if (d > e.max) e.max = d;
}

std::vector<Fragment> fragments_of(const Scene& scene, const RasterState& st) {
  std::vector<Fragment> out;
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) { out.push_back(f); });
  return out;
}

// One newton render's errors against the exact fragment stream.
RecipGridRow compare_with_exact(const Scene& scene, const RasterState& st, const std::vector<Fragment>& exact) {
  RecipGridRow row{st.recip_seed_bits, st.recip_iterations, {}, {}};
  size_t i = 0;
  const std::string setting =
      std::to_string(st.recip_seed_bits) + " seed bits, " + std::to_string(st.recip_iterations) + " iterations";
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) {
    if (i >= exact.size() || f.x != exact[i].x || f.y != exact[i].y || f.mask != exact[i].mask)
      throw SceneError("interp.recip = newton (" + setting + ") changed fragment " + std::to_string(i) +
                       "'s position or coverage: the reciprocal must reach attributes only");
    const Fragment& e = exact[i++];
    add_error(row.colour, f.r, e.r);
    add_error(row.colour, f.g, e.g);
    add_error(row.colour, f.b, e.b);
    add_error(row.texcoord, f.s, e.s);
    add_error(row.texcoord, f.t, e.t);
  });
  if (i != exact.size())
    throw SceneError("interp.recip = newton (" + setting + ") made " + std::to_string(i) + " fragments, exact " +
                     std::to_string(exact.size()));
  return row;
}

}  // namespace

RecipGrid recip_grid(const Scene& scene, const RasterState& arch, int max_seed_bits, int max_iterations) {
  RasterState st = arch;
  st.recip = RecipMethod::Exact;
  const std::vector<Fragment> exact = fragments_of(scene, st);
  RecipGrid grid;
  grid.fragments = exact.size();
  st.recip = RecipMethod::Newton;
  for (int it = 0; it <= max_iterations; ++it)
    for (int b = 1; b <= max_seed_bits; ++b) {
      st.recip_iterations = it;
      st.recip_seed_bits = b;
      grid.rows.push_back(compare_with_exact(scene, st, exact));
    }
  return grid;
}

}  // namespace rastsim
