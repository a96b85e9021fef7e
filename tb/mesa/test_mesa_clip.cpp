// SPDX-License-Identifier: Apache-2.0
// The geometry front end against Mesa's llvmpipe (docs/mesa.md, "Clip space"): seeded
// random clip-space triangles through both, one triangle a render, with the exact
// geometry in double (clip_geometry.h) as the oracle.
//
// - Coverage must be equal on every pixel whose centre is farther than one coordinate
//   LSB from every edge of the exact visible polygon; the differing pixels within that
//   LSB are counted and reported.
// - Colour (perspective-correct, smooth-shaded) within 1 LSB of llvmpipe's on interior
//   pixels, cut triangles included (with a guard band, on uncut triangles); both are also
//   held against the exact colour.
// - Hand-worked examples fix the orientation (NDC y = -1 is the top row of the
//   viewport_xform rectangle) and the fill rule on screen, independently of both.
// - Negative controls: the reference given the near plane moved by 1/64 w must disagree
//   in coverage; affine interpolation must disagree in colour.
// Reference configuration: configs/d3d11.toml (s15.8, as llvmpipe's 8 sub-pixel bits) at
// 240 x 160. Without a front end in the reference model (clip-space commands drawing
// nothing), the reference comparisons are skipped and only llvmpipe is held against the
// oracle. Seeds: RASTSIM_MESA_SEED (decimal) replaces the default base seed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "clip_compare.h"
#include "clip_geometry.h"
#include "clip_scenes.h"
#include "config/config.h"
#include "config/raster_state_config.h"
#include "osmesa_clip.h"

namespace rastsim::mesa {
namespace {

constexpr size_t kMaxReported = 10;
constexpr int kScenesPerKind = 6, kTrisPerScene = 250;  // 7 kinds: 10,500 triangles

RasterState clip_state(const std::vector<std::string>& overrides = {}) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/d3d11.toml");
  cfg.apply_override("display.width=240");
  cfg.apply_override("display.height=160");
  for (const std::string& o : overrides) cfg.apply_override(o);
  return raster_state_from_config(cfg);
}

// One llvmpipe clip-space context per framebuffer size and process.
OsMesaClipRenderer& renderer(const RasterState& st) {
  static std::map<std::pair<int, int>, std::unique_ptr<OsMesaClipRenderer>> contexts;
  auto& c = contexts[{st.fb_width, st.fb_height}];
  if (!c) c = std::make_unique<OsMesaClipRenderer>(st.fb_width, st.fb_height);
  return *c;
}

uint64_t base_seed() {
  const char* s = std::getenv("RASTSIM_MESA_SEED");
  return s ? std::strtoull(s, nullptr, 10) : 20261127;
}

// Why the reference model cannot be compared under st: empty when it draws clip-space
// triangles; otherwise the reason (no front end yet, or the error it gives, e.g. for a
// clip.method it does not model).
std::string front_end_missing(const RasterState& st) {
  try {
    return reference_draws_clip_space(st) ? ""
                                          : "the reference model draws no clip-space triangle (no geometry front end)";
  } catch (const std::exception& e) {
    return std::string("the reference model cannot draw clip space in this configuration: ") + e.what();
  }
}

ClipVertex vtx(float x, float y, uint8_t r = 255, uint8_t g = 255, uint8_t b = 255) {
  ClipVertex v;
  v.x = x, v.y = y, v.z = 0.5f, v.w = 1.0f, v.r = r, v.g = g, v.b = b;
  return v;
}

std::vector<std::string> rows(const std::vector<uint32_t>& img, int fb_w, int x0, int y0, int w, int h) {
  std::vector<std::string> out;
  for (int y = y0; y < y0 + h; ++y) {
    std::string row;
    for (int x = x0; x < x0 + w; ++x) row += (img[size_t(y) * fb_w + x] >> 24) ? '1' : '0';
    out.push_back(row);
  }
  return out;
}

TEST(MesaClipSetup, LlvmpipeWithClipControl) {
  OsMesaClipRenderer& gl = renderer(clip_state());
  std::cout << "llvmpipe: " << gl.renderer_name() << ", GL " << gl.version() << "\n";
  EXPECT_NE(gl.renderer_name().find("llvmpipe"), std::string::npos) << gl.renderer_name();
}

// The upper-left half of a 128 x 128 viewport_xform at (16, 8) in a 240 x 160
// framebuffer: clip-space corners (-1, -1), (1, -1), (-1, 1), w = 1. By hand: NDC y = -1
// is the top row (y = 8), NDC x = -1 the left column (x = 16); pixel (16 + i, 8 + j) has
// its centre inside when i + j + 1 < 128; on the diagonal (i + j + 1 = 128) the centre
// is on the triangle's bottom-right edge, which the top-left rule leaves out. So 8,128
// pixels, 127 in the top row, none in the bottom row or outside the rectangle.
void check_upper_left_half(const std::vector<uint32_t>& img, const RasterState& st, const char* who) {
  const ViewRect vp{16, 8, 128, 128};
  uint64_t total = 0, wrong = 0;
  for (int y = 0; y < st.fb_height; ++y)
    for (int x = 0; x < st.fb_width; ++x) {
      const int i = x - vp.x, j = y - vp.y;
      const bool expect = i >= 0 && j >= 0 && i < vp.width && j < vp.height && i + j + 1 < 128;
      const bool got = img[size_t(y) * st.fb_width + x] >> 24;
      total += got;
      wrong += got != expect;
    }
  EXPECT_EQ(total, 8128u) << who;
  EXPECT_EQ(wrong, 0u) << who << ": pixels differing from the hand-worked half";
  EXPECT_EQ(rows(img, st.fb_width, vp.x, vp.y, 128, 1)[0], std::string(127, '1') + "0") << who << ": top row";
  EXPECT_EQ(rows(img, st.fb_width, vp.x, vp.y + 127, 128, 1)[0], std::string(128, '0')) << who << ": bottom row";
}

// The square (8.5, 0.5)-(14.5, 6.5) of the same viewport split along its diagonal, as
// test_mesa_coverage.cpp's screen-space one, now given in clip space: NDC = (px - 64) /
// 64, exact in binary32. By hand (top-left rule, y down): the upper-right triangle owns
// the top row and the diagonal, the lower-left one the left column; the right column
// and the bottom row belong to neither.
void check_split_square(const std::vector<uint32_t>& upper_right, const std::vector<uint32_t>& lower_left,
                        const RasterState& st, const char* who) {
  const char* expected[] = {"11111100", "21111100", "22111100", "22211100", "22221100", "22222100",
                            "00000000", "00000000"};
  for (int y = 0; y < 8; ++y) {
    std::string row;
    for (int x = 0; x < 8; ++x) {
      const size_t p = size_t(8 + y) * st.fb_width + size_t(16 + 8 + x);
      row += char('0' + ((upper_right[p] >> 24) ? 1 : 0) + ((lower_left[p] >> 24) ? 2 : 0));
    }
    EXPECT_EQ(row, expected[y]) << who << ", row " << y << " of the square";
  }
}

std::vector<ClipTri> split_square() {
  const auto n = [](double px) { return float((px - 64) / 64); };
  return {ClipTri{{vtx(n(8.5), n(0.5)), vtx(n(14.5), n(0.5)), vtx(n(14.5), n(6.5))}},
          ClipTri{{vtx(n(8.5), n(0.5)), vtx(n(14.5), n(6.5)), vtx(n(8.5), n(6.5))}}};
}

const ClipTri kUpperLeftHalf{{vtx(-1, -1), vtx(1, -1), vtx(-1, 1)}};

TEST(MesaClipOrientation, LlvmpipeMinusWIsTheTopRow) {
  const RasterState st = clip_state();
  OsMesaClipRenderer& gl = renderer(st);
  const ViewRect vp{16, 8, 128, 128};
  check_upper_left_half(gl.render({kUpperLeftHalf}, vp), st, "llvmpipe");
  const std::vector<ClipTri> sq = split_square();
  check_split_square(gl.render({sq[0]}, vp), gl.render({sq[1]}, vp), st, "llvmpipe");
}

TEST(MesaClipOrientation, ReferenceMinusWIsTheTopRow) {
  const RasterState st = clip_state();
  if (const std::string why = front_end_missing(st); !why.empty()) GTEST_SKIP() << why;
  const ViewRect vp{16, 8, 128, 128};
  check_upper_left_half(reference_image({kUpperLeftHalf}, vp, st).rgba, st, "rastsim");
  const std::vector<ClipTri> sq = split_square();
  check_split_square(reference_image({sq[0]}, vp, st).rgba, reference_image({sq[1]}, vp, st).rgba, st, "rastsim");
}

// With a guard band x and y are not clipped at the viewport, so the viewport_xform
// rectangle itself must bound the pixels, as OpenGL's viewport does: the upper-left half
// of the 128 x 128 rectangle at (16, 8) widened to three viewports on the right (corner
// (3, -1), inside a guard band of 4) covers, by hand, every pixel (16 + i, 8 + j) of the
// rectangle whose centre satisfies (i + 0.5) / 2 + (j + 0.5) < 128, and nothing else.
std::vector<uint32_t> beyond_rectangle_expected(const RasterState& st) {
  std::vector<uint32_t> img(size_t(st.fb_width) * size_t(st.fb_height), 0);
  for (int j = 0; j < 128; ++j)
    for (int i = 0; i < 128; ++i)
      if ((i + 0.5) / 2 + (j + 0.5) < 128) img[size_t(8 + j) * st.fb_width + size_t(16 + i)] = 0xff000000u;
  return img;
}

const ClipTri kBeyondRectangle{{vtx(-1, -1), vtx(3, -1), vtx(-1, 1)}};

TEST(MesaClipOrientation, LlvmpipeViewportBoundsAGuardBand) {
  const RasterState st = clip_state();
  const std::vector<uint32_t> want = beyond_rectangle_expected(st);
  const std::vector<uint32_t> got = renderer(st).render({kBeyondRectangle}, {16, 8, 128, 128});
  size_t wrong = 0;
  for (size_t p = 0; p < want.size(); ++p) wrong += (want[p] >> 24 != 0) != (got[p] >> 24 != 0);
  EXPECT_EQ(wrong, 0u);
}

TEST(MesaClipOrientation, ReferenceViewportBoundsAGuardBand) {
  const RasterState st = clip_state({"clip.guard_band=4"});
  if (const std::string why = front_end_missing(st); !why.empty()) GTEST_SKIP() << why;
  const std::vector<uint32_t> want = beyond_rectangle_expected(st);
  const std::vector<uint32_t> got = reference_image({kBeyondRectangle}, {16, 8, 128, 128}, st).rgba;
  size_t wrong = 0, outside = 0;
  for (int y = 0; y < st.fb_height; ++y)
    for (int x = 0; x < st.fb_width; ++x) {
      const size_t p = size_t(y) * st.fb_width + size_t(x);
      const bool g = got[p] >> 24 != 0;
      wrong += (want[p] >> 24 != 0) != g;
      outside += g && (x < 16 || x >= 144 || y < 8 || y >= 136);
    }
  EXPECT_EQ(outside, 0u) << "pixels outside the viewport_xform rectangle";
  EXPECT_EQ(wrong, 0u);
}

void print(const std::string& what, const ClipStats& s, double ms) {
  std::cout << what << ": " << s.triangles << " triangles (" << s.visible << " visible), covered rastsim "
            << s.covered_reference << " / llvmpipe " << s.covered_llvmpipe << "; near an edge " << s.near_edge
            << " (" << s.near_mismatches << " differ: " << s.near_mismatches_by_edge[0] << " at a triangle edge, "
            << s.near_mismatches_by_edge[1] << " at the near or far line, " << s.near_mismatches_by_edge[2]
            << " at the viewport border); far mismatches " << s.far_mismatches
            << "; against exact coverage: llvmpipe " << s.llvmpipe_far_errors << ", rastsim " << s.reference_far_errors
            << "; colour on " << s.colour_pixels << " interior pixels: max |rastsim - llvmpipe| " << s.colour_max
            << " (" << s.colour_over_1 << " over 1, " << s.colour_over_1_cut << " of them on cut triangles, max " << s.colour_cut_max << "); "
            << s.colour_sensitive
            << " colour-sensitive pixels (max |rastsim - llvmpipe| " << s.sensitive_max
            << "); against exact: llvmpipe max " << s.llvmpipe_exact_max << " (" << s.llvmpipe_exact_over_1
            << " over 1), rastsim max " << s.reference_exact_max << " (" << s.reference_exact_over_1
            << " over 1); rastsim against its snapped-vertex colour: max " << s.reference_snapped_max << " ("
            << s.reference_snapped_over_1 << " over 1); repeated pixels " << s.repeats << "; " << ms << " ms\n";
}

void record(const ClipStats& s) {
  ::testing::Test::RecordProperty("triangles", std::to_string(s.triangles));
  ::testing::Test::RecordProperty("near_edge_pixels", std::to_string(s.near_edge));
  ::testing::Test::RecordProperty("near_edge_mismatches", std::to_string(s.near_mismatches));
  ::testing::Test::RecordProperty("far_mismatches", std::to_string(s.far_mismatches));
  ::testing::Test::RecordProperty("colour_pixels", std::to_string(s.colour_pixels));
  ::testing::Test::RecordProperty("colour_max_lsb", std::to_string(s.colour_max));
  ::testing::Test::RecordProperty("colour_sensitive_pixels", std::to_string(s.colour_sensitive));
}

// A reference configuration the random scenes are drawn with (config overrides on top
// of clip_state()), how many scenes of kTrisPerScene triangles a kind gets, and whether
// colour must be within 1 LSB on cut triangles too (else on uncut ones).
struct Variant {
  const char* name;
  std::vector<std::string> overrides;
  int scenes;
  bool cut_colour_within_1;
};
// clip (the default, guard band 1: x/y clipped exactly where llvmpipe clips them) on
// every scene; a guard band (x/y clipped only beyond 4 viewports, so the rectangle of
// viewport_xform must bound the pixels) and homogeneous rasterization on fewer. With the
// guard band, triangles llvmpipe cuts at +-w are drawn whole: 27 interior pixels of two
// kinds stay 2-4 LSB off (28 with 0 colour fraction bits, 27 with 8 or 13: docs/mesa.md).
const Variant kVariants[] = {{"Clip", {}, kScenesPerKind, true},
                             {"GuardBand4", {"clip.guard_band=4"}, 2, false},
                             {"Homogeneous", {"clip.method=homogeneous"}, 1, true}};  // 1,750 triangles: CI time

struct ClipCase {
  ClipKind kind;
  const Variant* variant;
};
void PrintTo(const ClipCase& c, std::ostream* os) { *os << to_string(c.kind) << "_" << c.variant->name; }

std::vector<ClipCase> clip_cases() {
  std::vector<ClipCase> out;
  for (const Variant& v : kVariants)
    for (ClipKind k : kClipKinds) out.push_back({k, &v});
  return out;
}

uint64_t scene_seed(ClipKind kind, int scene) { return base_seed() * 1000 + uint64_t(kind) * 100 + uint64_t(scene); }

// Draws `scenes` seeded scenes of `kind` through both (each with its own viewport_xform)
// and reports up to max_report mismatches a scene as failures naming the seed (0 for the
// negative controls, whose mismatches are expected). `reference_input` changes what the
// reference model is given.
using TriEdit = std::function<std::vector<ClipTri>(const std::vector<ClipTri>&)>;
ClipStats run_scenes(ClipKind kind, int scenes, const RasterState& st, bool with_reference, size_t max_report,
                     const TriEdit& reference_input = {}) {
  OsMesaClipRenderer& gl = renderer(st);
  ClipStats total;
  for (int s = 0; s < scenes; ++s) {
    const uint64_t seed = scene_seed(kind, s);
    SCOPED_TRACE(std::string(to_string(kind)) + " seed " + std::to_string(seed));
    const std::vector<ClipTri> tris = make_clip_scene(kind, seed, kTrisPerScene);
    const ViewRect vp = make_view_rect(seed, st.fb_width, st.fb_height);
    const std::vector<ClipTri> ref_tris = reference_input ? reference_input(tris) : tris;
    std::vector<ClipMismatch> report;
    total += compare_clip(tris, vp, st, gl, with_reference, report, max_report, &ref_tris);
    for (const ClipMismatch& m : report) ADD_FAILURE() << "seed " << seed << ": " << describe(m, tris, vp);
  }
  return total;
}

class MesaClip : public ::testing::TestWithParam<ClipCase> {};

TEST_P(MesaClip, CoverageAndColourAgainstLlvmpipe) {
  const ClipCase& c = GetParam();
  const RasterState st = clip_state(c.variant->overrides);
  const std::string missing = front_end_missing(st);
  const bool with_reference = missing.empty();
  if (!with_reference && c.variant != &kVariants[0]) GTEST_SKIP() << missing;
  const auto t0 = std::chrono::steady_clock::now();
  const ClipStats total = run_scenes(c.kind, c.variant->scenes, st, with_reference, kMaxReported);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const uint64_t seed0 = scene_seed(c.kind, 0);
  print("mesa clip " + std::string(to_string(c.kind)) + " " + c.variant->name + ", seeds " + std::to_string(seed0) +
            ".." + std::to_string(seed0 + uint64_t(c.variant->scenes) - 1),
        total, ms);
  record(total);
  EXPECT_EQ(total.llvmpipe_far_errors, 0u) << "llvmpipe against the exact coverage";
  if (!with_reference) GTEST_SKIP() << missing << ": only llvmpipe was held against the oracle";
  EXPECT_EQ(total.far_mismatches, 0u);
  EXPECT_EQ(total.reference_far_errors, 0u) << "rastsim against the exact coverage";
  if (c.variant->cut_colour_within_1)
    EXPECT_EQ(total.colour_over_1, 0u) << "colour more than 1 LSB off (" << total.colour_over_1_cut
                                       << " on cut triangles)";
  else
    EXPECT_EQ(total.colour_over_1, total.colour_over_1_cut) << "colour more than 1 LSB off on an uncut triangle";
  EXPECT_EQ(total.repeats, 0u) << "a clipped polygon's fan covered a pixel twice";
}

INSTANTIATE_TEST_SUITE_P(Kinds, MesaClip, ::testing::ValuesIn(clip_cases()), [](const auto& info) {
  return std::string(to_string(info.param.kind)) + "_" + info.param.variant->name;
});

// Negative control for coverage: the reference given the near-crossing scenes with the
// near plane moved by 1/64 w (z + w/64) must disagree with llvmpipe away from the edges.
TEST(MesaClipNegativeControl, NearPlaneMovedDisagrees) {
  const RasterState st = clip_state();
  if (const std::string why = front_end_missing(st); !why.empty()) GTEST_SKIP() << why;
  const ClipStats s = run_scenes(ClipKind::NearCrossing, 1, st, true, 0, [](const std::vector<ClipTri>& tris) {
    std::vector<ClipTri> moved = tris;
    for (ClipTri& t : moved)
      for (ClipVertex& v : t.v) v.z += v.w / 64;
    return moved;
  });
  std::cout << "near plane moved by w/64: " << s.far_mismatches << " far coverage mismatches\n";
  EXPECT_GT(s.far_mismatches, 0u);
}

// Negative control for colour: affine interpolation (interp.perspective = false) must
// differ from llvmpipe's perspective-correct colour by more than 1 LSB somewhere.
TEST(MesaClipNegativeControl, AffineColourDisagrees) {
  const RasterState st = clip_state({"interp.perspective=false"});
  if (const std::string why = front_end_missing(st); !why.empty()) GTEST_SKIP() << why;
  const ClipStats s = run_scenes(ClipKind::Camera, 1, st, true, 0);
  std::cout << "affine colour: " << s.colour_over_1 << " of " << s.colour_pixels
            << " interior pixels differ by more than 1 LSB (max " << s.colour_max << ")\n";
  EXPECT_GT(s.colour_over_1, 0u);
}

}  // namespace
}  // namespace rastsim::mesa
