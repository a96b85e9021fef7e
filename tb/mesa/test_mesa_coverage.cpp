// SPDX-License-Identifier: Apache-2.0
// The reference model against Mesa's llvmpipe (docs/mesa.md): the same seeded random
// triangle scenes through both, coverage identical pixel for pixel.
//
// - The reference model runs configs/d3d11.toml (s15.8 coordinates: 8 sub-pixel bits,
//   top-left rule, no culling); llvmpipe runs the D3D11-like state of OsMesaRenderer.
// - Every vertex is on the 1/256 px grid, so both snap without rounding (rastsim's
//   round-to-nearest-even relative to the viewport centre, llvmpipe's (v - 0.5) * 256
//   rounding, agree trivially); docs/mesa.md says why this is the comparison to make.
// - A hand-worked square split through pixel centres fixes the orientation of the
//   llvmpipe set-up (which rows are "top") independently of both renderers.
// - A negative control (reference with the bottom-right rule) must disagree, so the
//   comparison can fail.
// Seeds: RASTSIM_MESA_SEED (decimal) replaces the default base seed; every test prints
// the seed of each scene it draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "coverage_compare.h"
#include "mesa_scenes.h"
#include "osmesa_renderer.h"

namespace rastsim::mesa {
namespace {

constexpr size_t kMaxReported = 20;  // mismatches spelled out per test

RasterState d3d11_state() {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  return raster_state_from_config(cfg);
}

// One llvmpipe context per process (ctest runs each test in its own process).
OsMesaRenderer& renderer(const RasterState& st) {
  static OsMesaRenderer gl(st.fb_width, st.fb_height);
  return gl;
}

uint64_t base_seed() {
  const char* s = std::getenv("RASTSIM_MESA_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20261124;
}

TEST(MesaSetup, ReferenceIsD3d11AndRendererIsLlvmpipe) {
  const RasterState st = d3d11_state();
  EXPECT_EQ(st.coord_format.frac_bits, kSubpixelBits);
  EXPECT_EQ(st.fill_rule, FillRule::TopLeft);
  EXPECT_EQ(st.cull, CullMode::None);
  OsMesaRenderer& gl = renderer(st);
  std::cout << "llvmpipe: " << gl.renderer_name() << ", GL " << gl.version() << "\n";
  EXPECT_NE(gl.renderer_name().find("llvmpipe"), std::string::npos) << gl.renderer_name();
}

// The square (8.5, 0.5)-(14.5, 6.5) split along its diagonal, every edge through pixel
// centres. By hand, under the top-left rule (y down): the upper-right triangle owns the
// top row (its top edge) and the diagonal (its left edge); the lower-left one owns the
// left column; nobody owns the right column (x = 14) or the bottom row (y = 6).
TEST(MesaSetup, HandWorkedSquareSplitThroughPixelCentres) {
  const RasterState st = d3d11_state();
  constexpr int64_t c = 128;  // half a pixel, raw
  const std::vector<GridTri> tris = {
      {{8 * 256 + c, 14 * 256 + c, 14 * 256 + c}, {c, c, 6 * 256 + c}},          // upper right: bit 0
      {{8 * 256 + c, 14 * 256 + c, 8 * 256 + c}, {c, 6 * 256 + c, 6 * 256 + c}},  // lower left: bit 1
  };
  const char* expected[] = {
      // x = 8 .. 15, '1' upper right, '2' lower left
      "11111100", "21111100", "22111100", "22211100", "22221100", "22222100", "00000000", "00000000",
  };
  const auto check = [&](const std::vector<uint32_t>& m, const char* who) {
    for (int y = 0; y < 8; ++y) {
      std::string row;
      for (int x = 8; x < 16; ++x) row += char('0' + m[size_t(y) * st.fb_width + x]);
      EXPECT_EQ(row, expected[y]) << who << ", row " << y;
    }
    uint64_t total = 0;
    for (uint32_t v : m) total += v != 0;
    EXPECT_EQ(total, 36u) << who << ": pixels outside the square";  // 6 x 6 centres
  };
  check(reference_masks(tris, st), "rastsim");
  check(renderer(st).coverage_masks(tris), "llvmpipe");
}

struct KindCase {
  SceneKind kind;
  int scenes;
  int tris_per_scene;
};
void PrintTo(const KindCase& c, std::ostream* os) { *os << to_string(c.kind); }

class MesaCoverage : public ::testing::TestWithParam<KindCase> {};

TEST_P(MesaCoverage, IdenticalToReference) {
  const KindCase& kc = GetParam();
  const RasterState st = d3d11_state();
  OsMesaRenderer& gl = renderer(st);
  const auto t0 = std::chrono::steady_clock::now();
  CompareStats total;
  for (int s = 0; s < kc.scenes; ++s) {
    const uint64_t seed = base_seed() * 1000 + uint64_t(kc.kind) * 100 + uint64_t(s);
    SCOPED_TRACE("scene " + std::string(to_string(kc.kind)) + " seed " + std::to_string(seed));
    const std::vector<GridTri> tris = make_scene(kc.kind, seed, kc.tris_per_scene, st.fb_width, st.fb_height);
    std::vector<Mismatch> report;
    const CompareStats cs = compare_coverage(tris, st, gl, report, kMaxReported);
    total += cs;
    std::cout << "mesa " << to_string(kc.kind) << " seed " << seed << ": " << cs.triangles << " triangles, "
              << cs.covered << " covered pixels (" << cs.ties << " on an edge), " << cs.mismatches << " mismatches\n";
    for (const Mismatch& m : report) ADD_FAILURE() << "seed " << seed << ": " << describe(m, tris);
    EXPECT_EQ(cs.mismatches, 0u) << "seed " << seed << " (rerun: RASTSIM_MESA_SEED=" << base_seed() << ")";
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "mesa " << to_string(kc.kind) << " total: " << total.triangles << " triangles in " << total.passes
            << " passes, " << total.decisions << " (triangle, pixel) decisions, " << total.covered
            << " covered, " << total.ties << " centres on an edge, " << total.mismatches << " mismatches, " << ms
            << " ms\n";
  RecordProperty("triangles", std::to_string(total.triangles));
  RecordProperty("covered", std::to_string(total.covered));
  RecordProperty("mismatches", std::to_string(total.mismatches));
}

// Snapping probe: the same scenes with every coordinate moved by up to half an 8-bit
// LSB (2^-9 or 2^-10 px grid, exact ties included), so both rasterizers must round.
TEST_P(MesaCoverage, OffGridSnapping) {
  const KindCase& kc = GetParam();
  const RasterState st = d3d11_state();
  OsMesaRenderer& gl = renderer(st);
  CompareStats total;
  for (int extra = 1; extra <= 2; ++extra)
    for (int s = 0; s < kc.scenes; ++s) {
      const uint64_t seed = base_seed() * 1000 + uint64_t(kc.kind) * 100 + uint64_t(s);
      SCOPED_TRACE("scene " + std::string(to_string(kc.kind)) + " seed " + std::to_string(seed));
      const std::vector<GridTri> tris =
          off_grid(make_scene(kc.kind, seed, kc.tris_per_scene, st.fb_width, st.fb_height), extra, seed);
      std::vector<Mismatch> report;
      const CompareStats cs = compare_coverage(tris, st, gl, report, kMaxReported);
      total += cs;
      for (const Mismatch& m : report) ADD_FAILURE() << "seed " << seed << " +" << extra << " bits: " << describe(m, tris);
      EXPECT_EQ(cs.mismatches, 0u) << "seed " << seed << " +" << extra << " bits";
    }
  const uint64_t seed0 = base_seed() * 1000 + uint64_t(kc.kind) * 100;
  std::cout << "mesa off-grid " << to_string(kc.kind) << " seeds " << seed0 << ".." << seed0 + kc.scenes - 1
            << " total: " << total.triangles << " triangles, "
            << total.covered << " covered, " << total.mismatches << " mismatches\n";
}

INSTANTIATE_TEST_SUITE_P(Scenes, MesaCoverage,
                         ::testing::Values(KindCase{SceneKind::Tiny, 16, 256}, KindCase{SceneKind::Sliver, 16, 128},
                                           KindCase{SceneKind::Large, 8, 64}, KindCase{SceneKind::Mesh, 16, 192},
                                           KindCase{SceneKind::Fan, 16, 160}),
                         [](const auto& info) { return std::string(to_string(info.param.kind)); });

// Which snapping llvmpipe does, without trusting rastsim's: llvmpipe is given a mesh
// with coordinates up to half an LSB off the grid (2^-9 px: every offset is 0 or an
// exact tie); the reference model is given the same mesh rounded on the test side.
// Ties to even must agree everywhere, ties up must not, so the off-grid tests above
// can see a rounding difference.
TEST(MesaSnapping, LlvmpipeRoundsTiesToEven) {
  const RasterState st = d3d11_state();
  OsMesaRenderer& gl = renderer(st);
  const uint64_t seed = base_seed() * 1000 + 998;
  std::cout << "mesa snapping seed " << seed << "\n";
  const std::vector<GridTri> off = off_grid(make_scene(SceneKind::Mesh, seed, 256, st.fb_width, st.fb_height), 1, seed);
  uint64_t mismatches[2] = {};
  for (int even = 0; even < 2; ++even) {
    const std::vector<GridTri> snapped = snap_to_grid(off, even == 1);
    for (size_t first = 0; first < off.size(); first += kMaxTrisPerPass) {
      const size_t last = std::min(off.size(), first + kMaxTrisPerPass);
      const std::vector<uint32_t> ref =
          reference_masks({snapped.begin() + first, snapped.begin() + last}, st);
      const std::vector<uint32_t> lp = gl.coverage_masks({off.begin() + first, off.begin() + last});
      for (size_t p = 0; p < ref.size(); ++p) mismatches[even] += uint64_t(std::popcount(ref[p] ^ lp[p]));
    }
  }
  std::cout << "llvmpipe (off grid) against reference (pre-rounded): ties up " << mismatches[0]
            << " mismatches, ties to even " << mismatches[1] << "\n";
  EXPECT_EQ(mismatches[1], 0u);
  EXPECT_GT(mismatches[0], 0u);
}

// Negative control: the reference with the bottom-right rule must disagree with
// llvmpipe on a mesh (ties on shared edges through pixel centres), or the comparison
// is blind.
TEST(MesaNegativeControl, BottomRightRuleDisagrees) {
  RasterState st = d3d11_state();
  OsMesaRenderer& gl = renderer(st);
  st.fill_rule = FillRule::BottomRight;
  const uint64_t seed = base_seed() * 1000 + 999;
  std::cout << "mesa negative control seed " << seed << "\n";
  const std::vector<GridTri> tris = make_scene(SceneKind::Mesh, seed, 128, st.fb_width, st.fb_height);
  std::vector<Mismatch> report;
  const CompareStats cs = compare_coverage(tris, st, gl, report, 1);
  std::cout << "bottom-right reference against llvmpipe: " << cs.mismatches << " mismatches\n";
  EXPECT_GT(cs.mismatches, 0u);
}

}  // namespace
}  // namespace rastsim::mesa
