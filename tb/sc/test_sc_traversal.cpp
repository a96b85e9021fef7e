// SPDX-License-Identifier: Apache-2.0
// The timed model under every raster.traversal method: the image, the fragment stream
// (in the method's order) and the counters equal the reference model's on random scenes
// and the shipped traces; the fine and coarse raster spend the cycles of the cost
// equations (docs/traversal.md), computed here from the reference model's setup and
// span functions, not from the timed model.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "config/raster_state_config.h"
#include "sim_harness.h"
#include "ref/prim_assembly.h"
#include "ref/traverse.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

const std::vector<std::vector<std::string>> kMethods = {
    {"raster.traversal=tiled"},
    {"raster.traversal=bbox"},
    {"raster.traversal=hierarchical"},
    {"raster.traversal=hierarchical", "raster.hier_levels=32/8/2", "fifo.tile_depth=1"},
    {"raster.traversal=scanline", "raster.scanline_arith=f32"},
    {"raster.traversal=scanline", "raster.scanline_arith=f64", "fifo.pixel_depth=1"},
    {"raster.traversal=scanline", "raster.scanline_arith=fixed"},
};

TEST(ScTraversal, EveryMethodMatchesReference) {
  for (const auto& m : kMethods) {
    SCOPED_TRACE(m[0] + (m.size() > 1 ? " " + m[1] : ""));
    for (uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      const Scene scene = random_scene(seed, 128, 96, 60);
      auto sets = m;
      sets.push_back("raster.depth_func=less");
      const Config cfg = make_config(sets);
      sc::SimOptions o;
      if (seed == 2) {
        o.stall_seed = seed;
        o.stall_probability = 0.2;
      }
      expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg, o); }));
    }
    for (const auto& path : shipped_traces()) {
      SCOPED_TRACE(path);
      const Scene scene = load_trace(path);
      auto sets = m;
      sets.insert(sets.end(), {"raster.depth_func=less", "raster.out_of_range=cull"});
      for (const auto& c : scene.commands)
        if (const auto* v = std::get_if<CmdViewport>(&c.body)) {
          sets.push_back("display.width=" + std::to_string(std::max(128, v->width)));
          sets.push_back("display.height=" + std::to_string(std::max(128, v->height)));
        }
      expect_matches_reference(run_isolated([&, cfg = make_config(sets)] { return compare_with_reference(scene, cfg); }));
    }
  }
}

// One triangle, so the coarse and fine raster's busy cycles are one walk each.
Scene one_triangle() {
  return parse_trace("viewport 96 80\ntri 3.3 2.1 0.5 255 0 0 90.7 20.2 0.5 0 255 0 30.1 77.6 0.5 0 0 255\n",
                     "one_triangle");
}

TEST(ScTraversal, CostEquations) {
  const Scene scene = one_triangle();
  const std::vector<std::string> base{"display.width=96", "display.height=80", "fine.samples_per_cycle=8",
                                      "coarse.tiles_per_cycle=1", "coarse.scanline_setup_cycles=5",
                                      "fine.span_setup_cycles=2", "fine.span_pixels_per_cycle=4"};
  // The set-up triangle, from the reference model.
  const Config cfg0 = make_config(base);
  const RasterState st = raster_state_from_config(cfg0);
  SetupTriangle t;
  ASSERT_EQ(setup_triangle(assemble_triangle(std::get<CmdPrimitives>(scene.commands[1].body), 0), st, SourceLoc{}, t),
            SetupOutcome::Accepted);
  auto busy = [&](const std::vector<std::string>& extra, const char* stage) {
    auto sets = base;
    sets.insert(sets.end(), extra.begin(), extra.end());
    const auto j = run_isolated([&, cfg = make_config(sets)] { return simulate_stats(scene, cfg); });
    EXPECT_FALSE(j.contains("error")) << j.dump();
    return std::make_pair(j["stages"][stage]["busy"].get<uint64_t>(), j);
  };
  // Every stage also passes the viewport command, in 1 cycle: the "1 +" below.
  // bbox: the box's pixels at 8 a cycle, and the coarse raster 1 cycle.
  EXPECT_EQ(busy({"raster.traversal=bbox"}, "fine_raster").first, 1 + uint64_t((t.bbox.area() + 7) / 8));
  EXPECT_EQ(busy({"raster.traversal=bbox"}, "coarse_raster").first, 1 + 1u);
  // hierarchical: one cycle per tile classified at every level.
  const auto [hb, hj] = busy({"raster.traversal=hierarchical"}, "coarse_raster");
  EXPECT_EQ(hb, 1 + hj["tiles_visited"].get<uint64_t>());
  // scanline: setup + one cycle a row in the box; per span 2 + ceil(n / 4).
  uint64_t rows = 0, fine = 0;
  scanline_spans(t, DdaArith::F32, st.coord_format.frac_bits, [&](int, int x0, int x1) {
    ++rows;
    if (x1 > x0) fine += 2 + uint64_t(x1 - x0 + 3) / 4;
  });
  EXPECT_GT(rows, 60u);
  EXPECT_EQ(busy({"raster.traversal=scanline"}, "coarse_raster").first, 1 + 5 + rows);
  EXPECT_EQ(busy({"raster.traversal=scanline"}, "fine_raster").first, 1 + fine);
}

TEST(ScTraversal, EveryMethodCostsDifferentCycles) {
  const Scene scene = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace");
  std::set<uint64_t> cycles;
  for (const char* m : {"tiled", "bbox", "hierarchical", "scanline"}) {
    const auto j = run_isolated([&, cfg = make_config({std::string("raster.traversal=") + m})] {
      return simulate_stats(scene, cfg);
    });
    ASSERT_FALSE(j.contains("error")) << j.dump();
    cycles.insert(j["cycles"].get<uint64_t>());
  }
  EXPECT_EQ(cycles.size(), 4u);
}

}  // namespace
}  // namespace rastsim::sctest
