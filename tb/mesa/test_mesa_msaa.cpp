// SPDX-License-Identifier: Apache-2.0
// The reference model's 4x multisample coverage against llvmpipe's (docs/mesa.md,
// "4x multisampling"): the same seeded random scenes through both, the number of covered
// samples (and the sample mask itself) identical for every (triangle, pixel).
//
// - llvmpipe's 4x positions are asserted to be the standard D3D11/Vulkan ones, in the
//   same order, and equal to rastsim's snapped pattern.
// - A hand-worked case (expected masks by hand) pins the sample order and the top-left
//   rule per sample on horizontal and vertical shared edges.
// - The brief's counting method (each triangle alone in white, box-filter resolve,
//   k = round(4 v / 255)) is checked against the per-sample read-back the comparisons use.
// - Scenes: configs/d3d11.toml (s15.8, 640 x 480) with vertices on the 1/256 grid and
//   off it (snapping ties); configs/default.toml (s7.16, 128 x 128) with vertices on the
//   1/256 grid; and vertices on the s7.16 grid (2^-16 px), which llvmpipe rounds to
//   1/256: rastsim must then agree given the same rounding, and must not without it.
// Seeds: RASTSIM_MESA_SEED as in test_mesa_coverage.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "mesa_scenes.h"
#include "msaa_compare.h"
#include "osmesa_msaa.h"
#include "ref/sample_pattern.h"

namespace rastsim::mesa {
namespace {

constexpr size_t kMaxReported = 20;

RasterState state(const char* config, const std::vector<std::string>& overrides = {}) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + config);
  cfg.apply_override("raster.samples=" + std::to_string(kMsaaSamples));
  for (const std::string& o : overrides) cfg.apply_override(o);
  return raster_state_from_config(cfg);
}
RasterState d3d11_4x() { return state("d3d11.toml"); }
RasterState default_4x() { return state("default.toml"); }

// One 4x llvmpipe context per framebuffer size and process.
OsMesaMsaa& msaa(const RasterState& st) {
  static std::map<std::pair<int, int>, std::unique_ptr<OsMesaMsaa>> contexts;
  auto& c = contexts[{st.fb_width, st.fb_height}];
  if (!c) c = std::make_unique<OsMesaMsaa>(st.fb_width, st.fb_height);
  return *c;
}

uint64_t base_seed() {
  const char* s = std::getenv("RASTSIM_MESA_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20261124;
}

std::string stats_line(const MsaaStats& s) {
  return std::to_string(s.triangles) + " triangles, " + std::to_string(s.decisions) + " (triangle, pixel) pairs, " +
         std::to_string(s.pixels_covered) + " covered (" + std::to_string(s.pixels_partial) + " partially), " +
         std::to_string(s.samples_covered) + " samples covered (" + std::to_string(s.samples_on_edge) +
         " on an edge), " + std::to_string(s.count_mismatches) + " count mismatches, " +
         std::to_string(s.mask_mismatches) + " mask mismatches, " + std::to_string(s.pipeline_vs_direct) +
         " pipeline/direct differences";
}

// Compares, reports every mismatch (up to kMaxReported) and expects none.
MsaaStats expect_identical(const std::vector<GridTri>& tris, const RasterState& st, const std::string& what) {
  std::vector<MsaaMismatch> report;
  const MsaaStats cs = compare_msaa(tris, st, msaa(st), report, kMaxReported);
  for (const MsaaMismatch& m : report) ADD_FAILURE() << what << ": " << describe(m, tris);
  EXPECT_EQ(cs.mask_mismatches, 0u) << what << " (rerun: RASTSIM_MESA_SEED=" << base_seed() << ")";
  EXPECT_EQ(cs.pipeline_vs_direct, 0u) << what << ": render_scene and pixel_sample_mask differ";
  return cs;
}

TEST(MesaMsaaSetup, LlvmpipeHasTheStandardFourSamplePositions) {
  const RasterState st = d3d11_4x();
  OsMesaMsaa& gl = msaa(st);
  std::cout << "llvmpipe 4x: " << gl.renderer_name() << ", GL_SAMPLES " << gl.samples() << "\n";
  EXPECT_NE(gl.renderer_name().find("llvmpipe"), std::string::npos);
  ASSERT_EQ(gl.samples(), kMsaaSamples);
  const auto pos = gl.sample_positions();
  const auto& std16 = standard_sample_offsets_16th(kMsaaSamples);
  const SamplePattern& p8 = sample_pattern(kMsaaSamples, st.coord_format.frac_bits);
  const SamplePattern& p16 = sample_pattern(kMsaaSamples, default_4x().coord_format.frac_bits);
  const int standard[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};  // D3D11 4x, 1/16 px, y down
  for (int s = 0; s < kMsaaSamples; ++s) {
    std::cout << "sample " << s << ": llvmpipe (" << pos[s][0] << ", " << pos[s][1] << ") from the corner\n";
    for (int a = 0; a < 2; ++a) {
      // From the corner in 1/16 px: exact in binary32.
      EXPECT_EQ(pos[s][a] * 16.0f, float(8 + standard[s][a])) << "sample " << s << " axis " << a;
      EXPECT_EQ(std16[s][a], standard[s][a]) << "rastsim's table, sample " << s;
    }
    EXPECT_EQ(p8.dx[s], int64_t(standard[s][0]) * 16) << "s15.8 pattern";
    EXPECT_EQ(p8.dy[s], int64_t(standard[s][1]) * 16);
    EXPECT_EQ(p16.dx[s], int64_t(standard[s][0]) * 4096) << "s7.16 pattern";
    EXPECT_EQ(p16.dy[s], int64_t(standard[s][1]) * 4096);
  }
}

// Expected masks worked by hand (1/256 px units, y down; sample s of pixel (px, py) is at
// (px + 1/2 + dx_s/16, py + 1/2 + dy_s/16)):
// - bits 0, 1: triangles above and below the horizontal edge y = 20 + 2/16, through sample
//   0 of row 20. Top-left rule: the lower triangle (whose top edge it is) owns sample 0 of
//   pixel (20, 20) and the other three; the upper one has none there.
// - bits 2, 3: triangles left and right of the vertical edge x = 40 + 2/16, through sample
//   2 of column 40: the right one (its left edge) owns all four of pixel (40, 40).
// - bits 4..7: a 1/16-px triangle around sample k - 4 of pixel (60, 30) each: mask
//   1 << (k - 4) there and nothing anywhere else (pins the sample order).
TEST(MesaMsaaSetup, HandWorkedSampleOrderAndSharedEdges) {
  const RasterState st = d3d11_4x();
  constexpr int64_t px = 256, sx = 16;  // a pixel, a sixteenth, raw
  const int64_t ye = 20 * px + 2 * sx, xe = 40 * px + 2 * sx;
  std::vector<GridTri> tris = {
      {{16 * px, 24 * px, 20 * px}, {ye, ye, 16 * px}},  // above the horizontal edge
      {{16 * px, 24 * px, 20 * px}, {ye, ye, 24 * px}},  // below it
      {{xe, xe, 36 * px}, {36 * px, 44 * px, 40 * px}},  // left of the vertical edge
      {{xe, xe, 44 * px}, {36 * px, 44 * px, 40 * px}},  // right of it
  };
  const int standard[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
  for (int s = 0; s < 4; ++s) {
    const int64_t cx = 60 * px + px / 2 + standard[s][0] * sx, cy = 30 * px + px / 2 + standard[s][1] * sx;
    tris.push_back({{cx - 8, cx + 8, cx}, {cy - 8, cy - 8, cy + 8}});
  }
  const auto at = [&](int x, int y) { return size_t(y) * size_t(st.fb_width) + size_t(x); };
  const auto check = [&](const SampleMasks& m, const char* who) {
    EXPECT_EQ(tri_mask(m, at(20, 20), 0), 0u) << who;
    EXPECT_EQ(tri_mask(m, at(20, 20), 1), 0xfu) << who;
    EXPECT_EQ(tri_mask(m, at(40, 40), 2), 0u) << who;
    EXPECT_EQ(tri_mask(m, at(40, 40), 3), 0xfu) << who;
    for (int k = 4; k < 8; ++k) {
      EXPECT_EQ(tri_mask(m, at(60, 30), k), 1u << (k - 4)) << who << ", sample " << k - 4;
      uint64_t elsewhere = 0;
      for (size_t p = 0; p < m[0].size(); ++p)
        if (p != at(60, 30)) elsewhere += tri_mask(m, p, k) != 0;
      EXPECT_EQ(elsewhere, 0u) << who << ", tiny triangle " << k;
    }
  };
  check(reference_sample_masks(tris, st), "rastsim (pipeline)");
  check(direct_sample_masks(tris, st, nullptr), "rastsim (pixel_sample_mask)");
  check(msaa(st).sample_masks(tris), "llvmpipe");
}

// The per-sample read-back against the counting method of the brief: each
// triangle alone in white, resolved by glBlitFramebuffer, k = round(4 v / 255). Both
// llvmpipe; then the reference's popcount.
TEST(MesaMsaaSetup, ResolvedCountsAgreeWithSampleReadBack) {
  const RasterState st = d3d11_4x();
  OsMesaMsaa& gl = msaa(st);
  const uint64_t seed = base_seed() * 1000 + 997;
  std::vector<GridTri> tris = make_scene(SceneKind::Tiny, seed, 48, st.fb_width, st.fb_height);
  for (SceneKind k : {SceneKind::Sliver, SceneKind::Fan}) {
    const std::vector<GridTri> more = make_scene(k, seed, 16, st.fb_width, st.fb_height);
    tris.insert(tris.end(), more.begin(), more.end());
  }
  uint64_t pixels = 0, partial = 0, bad_resolve = 0, bad_ref = 0;
  for (size_t first = 0; first < tris.size(); first += kMaxTrisPerPass) {
    const std::vector<GridTri> b(tris.begin() + first, tris.begin() + std::min(tris.size(), first + kMaxTrisPerPass));
    const SampleMasks lp = gl.sample_masks(b);
    const SampleMasks ref = direct_sample_masks(b, st, nullptr);
    for (size_t i = 0; i < b.size(); ++i) {
      const std::vector<uint8_t> k = gl.resolved_counts(b[i]);
      for (size_t p = 0; p < k.size(); ++p) {
        pixels += k[p] != 0;
        partial += k[p] != 0 && k[p] != kMsaaSamples;
        bad_resolve += k[p] != std::popcount(tri_mask(lp, p, int(i)));
        bad_ref += k[p] != std::popcount(tri_mask(ref, p, int(i)));
      }
    }
  }
  std::cout << "resolve check seed " << seed << ": " << tris.size() << " triangles, " << pixels
            << " pixels covered (" << partial << " partially), " << bad_resolve
            << " resolve/read-back differences, " << bad_ref << " resolve/rastsim differences\n";
  EXPECT_GT(partial, 0u);
  EXPECT_EQ(bad_resolve, 0u);
  EXPECT_EQ(bad_ref, 0u);
}

struct MsaaCase {
  SceneKind kind;
  int scenes;
  int tris_per_scene;
};
void PrintTo(const MsaaCase& c, std::ostream* os) { *os << to_string(c.kind); }

uint64_t scene_seed(SceneKind kind, int s) { return base_seed() * 1000 + 500 + uint64_t(kind) * 20 + uint64_t(s); }

class MesaMsaa : public ::testing::TestWithParam<MsaaCase> {};

// s15.8, 640 x 480, every vertex on the 1/256 grid: nothing rounds.
TEST_P(MesaMsaa, SampleCountsIdenticalOnGrid) {
  const MsaaCase& c = GetParam();
  const RasterState st = d3d11_4x();
  const auto t0 = std::chrono::steady_clock::now();
  MsaaStats total;
  for (int s = 0; s < c.scenes; ++s) {
    const uint64_t seed = scene_seed(c.kind, s);
    const std::vector<GridTri> tris = make_scene(c.kind, seed, c.tris_per_scene, st.fb_width, st.fb_height);
    total += expect_identical(tris, st, std::string(to_string(c.kind)) + " seed " + std::to_string(seed));
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "mesa 4x " << to_string(c.kind) << " seeds " << scene_seed(c.kind, 0) << "..+" << c.scenes - 1
            << ": " << stats_line(total) << ", " << ms << " ms\n";
}

// The same scenes moved off the grid by up to half an LSB (2^-9 and 2^-10 px grids,
// exact ties included): both must round alike (ties to even). llvmpipe's multisample
// set-up snaps v * 256 (no half-pixel offset), rastsim (v - 320) * 256: the offset is a
// multiple of two LSBs, so ties go the same way.
TEST_P(MesaMsaa, SampleCountsIdenticalOffGrid) {
  const MsaaCase& c = GetParam();
  const RasterState st = d3d11_4x();
  MsaaStats total;
  for (int extra = 1; extra <= 2; ++extra)
    for (int s = 0; s < (c.scenes + 1) / 2; ++s) {
      const uint64_t seed = scene_seed(c.kind, s);
      const std::vector<GridTri> tris =
          off_grid(make_scene(c.kind, seed, c.tris_per_scene, st.fb_width, st.fb_height), extra, seed);
      total += expect_identical(tris, st,
                                std::string(to_string(c.kind)) + " seed " + std::to_string(seed) + " +" +
                                    std::to_string(extra) + " bits");
    }
  std::cout << "mesa 4x off-grid " << to_string(c.kind) << ": " << stats_line(total) << "\n";
}

INSTANTIATE_TEST_SUITE_P(Scenes, MesaMsaa,
                         ::testing::Values(MsaaCase{SceneKind::Tiny, 8, 256}, MsaaCase{SceneKind::Sliver, 8, 128},
                                           MsaaCase{SceneKind::Large, 4, 64}, MsaaCase{SceneKind::Mesh, 8, 192},
                                           MsaaCase{SceneKind::Fan, 8, 160}),
                         [](const auto& info) { return std::string(to_string(info.param.kind)); });

// Triangles of a 128 x 128 scene whose vertices all lie well inside s7.16's range
// (+-128 px about the viewport centre, 64): a margin of 8 px.
std::vector<GridTri> in_s7_16_range(const std::vector<GridTri>& tris) {
  std::vector<GridTri> out;
  const auto ok = [](int64_t raw, int f) { return raw >= (-56LL << f) && raw <= (184LL << f); };
  for (const GridTri& t : tris)
    if (std::all_of(t.x.begin(), t.x.end(), [&](int64_t v) { return ok(v, t.frac_bits); }) &&
        std::all_of(t.y.begin(), t.y.end(), [&](int64_t v) { return ok(v, t.frac_bits); }))
      out.push_back(t);
  return out;
}

std::vector<GridTri> small_fb_scene(int s, const RasterState& st) {
  static constexpr SceneKind kinds[] = {SceneKind::Tiny, SceneKind::Sliver, SceneKind::Mesh, SceneKind::Fan};
  const SceneKind k = kinds[s % 4];
  return in_s7_16_range(make_scene(k, scene_seed(k, 10 + s), 256, st.fb_width, st.fb_height));
}
constexpr int kSmallScenes = 16;  // four of each kind

// configs/default.toml (s7.16, 128 x 128) with vertices on the 1/256 grid: rastsim's
// 16 sub-pixel bits hold them exactly, llvmpipe's 8 do too, so nothing rounds.
TEST(MesaMsaaS7_16, SampleCountsIdenticalOnTheEightBitGrid) {
  const RasterState st = default_4x();
  ASSERT_EQ(st.coord_format.frac_bits, 16);
  MsaaStats total;
  for (int s = 0; s < kSmallScenes; ++s)
    total += expect_identical(small_fb_scene(s, st), st, "s7.16 scene " + std::to_string(s));
  std::cout << "mesa 4x s7.16, 1/256 grid: " << stats_line(total) << "\n";
}

// Vertices on the s7.16 grid itself (2^-16 px, up to half an 8-bit LSB off the 1/256
// grid; exact in binary32 at 128 px). llvmpipe can only round them to 1/256:
// - rastsim s7.16 given the same vertices rounded to 1/256 (ties to even, test side)
//   must agree exactly: the only difference is that rounding;
// - rastsim s15.8 (which rounds them itself) must agree exactly;
// - rastsim s7.16 given them unrounded must disagree (its extra precision is visible).
TEST(MesaMsaaS7_16, SixteenBitVerticesAgreeOnceRoundedToEightBits) {
  const RasterState st16 = default_4x();
  const RasterState st8 = state("d3d11.toml", {"display.width=128", "display.height=128"});
  ASSERT_EQ(st8.fb_width, st16.fb_width);
  MsaaStats rounded, own_rounding, unrounded;
  for (int s = 0; s < kSmallScenes / 2; ++s) {
    const std::vector<GridTri> tris = off_grid(small_fb_scene(s, st16), 8, scene_seed(SceneKind::Tiny, 40 + s));
    const std::vector<GridTri> snapped = snap_to_grid(tris, true);
    OsMesaMsaa& gl = msaa(st16);
    std::vector<MsaaMismatch> report;
    for (size_t first = 0; first < tris.size(); first += kMaxTrisPerPass) {
      const size_t last = std::min(tris.size(), first + kMaxTrisPerPass);
      const std::vector<GridTri> b(tris.begin() + first, tris.begin() + last);
      const std::vector<GridTri> bs(snapped.begin() + first, snapped.begin() + last);
      const SampleMasks lp = gl.sample_masks(b);
      const SampleMasks r16 = direct_sample_masks(bs, st16, nullptr);
      const SampleMasks r8 = direct_sample_masks(b, st8, nullptr);
      const SampleMasks raw = direct_sample_masks(b, st16, nullptr);
      for (size_t p = 0; p < lp[0].size(); ++p)
        for (size_t i = 0; i < b.size(); ++i) {
          const uint32_t l = tri_mask(lp, p, int(i));
          rounded.mask_mismatches += tri_mask(r16, p, int(i)) != l;
          own_rounding.mask_mismatches += tri_mask(r8, p, int(i)) != l;
          unrounded.mask_mismatches += tri_mask(raw, p, int(i)) != l;
          unrounded.count_mismatches += std::popcount(tri_mask(raw, p, int(i))) != std::popcount(l);
        }
      rounded.triangles += b.size();
    }
  }
  std::cout << "mesa 4x s7.16-grid vertices: " << rounded.triangles << " triangles; mask mismatches: rastsim s7.16 "
            << "pre-rounded " << rounded.mask_mismatches << ", rastsim s15.8 " << own_rounding.mask_mismatches
            << ", rastsim s7.16 unrounded " << unrounded.mask_mismatches << " (" << unrounded.count_mismatches
            << " in the count)\n";
  EXPECT_EQ(rounded.mask_mismatches, 0u);
  EXPECT_EQ(own_rounding.mask_mismatches, 0u);
  EXPECT_GT(unrounded.count_mismatches, 0u);
}

// Negative control: the reference with the bottom-right rule must disagree with
// llvmpipe's 4x coverage on meshes, or the comparison is blind to the rule per sample.
TEST(MesaMsaaNegativeControl, BottomRightRuleDisagrees) {
  RasterState st = d3d11_4x();
  st.fill_rule = FillRule::BottomRight;
  const std::vector<GridTri> tris = make_scene(SceneKind::Mesh, base_seed() * 1000 + 996, 128, st.fb_width, st.fb_height);
  std::vector<MsaaMismatch> report;
  const MsaaStats cs = compare_msaa(tris, st, msaa(st), report, 1);
  std::cout << "bottom-right reference against llvmpipe 4x: " << cs.mask_mismatches << " mask mismatches, "
            << cs.count_mismatches << " count mismatches\n";
  EXPECT_GT(cs.count_mismatches, 0u);
}

}  // namespace
}  // namespace rastsim::mesa
