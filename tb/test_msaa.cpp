// SPDX-License-Identifier: Apache-2.0
// Multisampling in the reference model (raster.samples, raster.aa_mode;
// docs/antialiasing.md), each part checked against a statement that does not use the
// code under test:
// - the snapped sample pattern: the D3D11 tables' offsets worked by hand to raw units;
// - sample coverage by translation: sample s of pixel p is covered by triangle T exactly
//   when the CENTRE of p is covered by T moved by -d_s (the edge rule is translation
//   invariant and d_s is a whole number of grid steps). The one-sample centre test is
//   itself checked against a big-integer reference (test_raster_exact.cpp). Every
//   traversal method's masks are compared with that brute force over the whole clip
//   rectangle, so a pixel outside the widened bounding box or a tile wrongly rejected or
//   accepted shows as a wrong mask;
// - ssaa attributes by the same translation; msaa attributes at the centre, extrapolated
//   and clamped, against barycentric weights from vertex cross products;
// - resolve rounding and per-sample depth on hand-worked pixels;
// - the errors of combinations the model does not support.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <random>
#include <utility>

#include "common/screen_vertex.h"
#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/fine_raster.h"
#include "ref/pipeline.h"
#include "ref/sample_pattern.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"

namespace rastsim {
namespace {

TEST(SamplePattern, StandardOffsetsSnappedToTheGrid) {
  // F = 16: 1/16 px is 4096 raw units, exactly.
  const SamplePattern& p4 = sample_pattern(4, 16);
  const int64_t want4[4][2] = {{-8192, -24576}, {24576, -8192}, {-24576, 8192}, {8192, 24576}};
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(p4.dx[size_t(s)], want4[s][0]) << s;
    EXPECT_EQ(p4.dy[size_t(s)], want4[s][1]) << s;
  }
  EXPECT_EQ(p4.dx_min, -24576);
  EXPECT_EQ(p4.dx_max, 24576);
  // 16x reaches -8/16: the pixel's left and top edges.
  EXPECT_EQ(sample_pattern(16, 16).dx_min, -32768);
  EXPECT_EQ(sample_pattern(16, 16).dy_min, -32768);
  EXPECT_EQ(sample_pattern(1, 16).dx[0], 0);
  // F = 2 (quarter pixels): -2/16 px = -0.5 raw -> 0 (tie to even), -6/16 px = -1.5 raw
  // -> -2 (tie to even), 6/16 -> 2, 2/16 -> 0.
  const SamplePattern& q = sample_pattern(4, 2);
  const int64_t wantq[4][2] = {{0, -2}, {2, 0}, {-2, 0}, {0, 2}};
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(q.dx[size_t(s)], wantq[s][0]) << s;
    EXPECT_EQ(q.dy[size_t(s)], wantq[s][1]) << s;
  }
  EXPECT_EQ(p4.full_mask(), 0xFu);
  EXPECT_EQ(sample_pattern(16, 16).full_mask(), 0xFFFFu);
  EXPECT_TRUE(valid_sample_count(8));
  EXPECT_FALSE(valid_sample_count(3));
}

constexpr int kF = 16;

RasterState small_state(int samples) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.viewport_width = 40;
  st.fb_height = st.viewport_height = 30;
  st.samples = samples;
  return st;
}

// The vertex colours setup_raw gives its triangles (RGB8).
constexpr std::array<uint32_t, 3> kRed{40, 140, 240}, kGreen{250, 140, 30}, kBlue{17, 77, 137};

// Sets up the triangle of absolute raw vertices (units 2^-F px from the framebuffer's
// corner).
SetupOutcome setup_raw(const std::array<int64_t, 6>& v, const RasterState& st, SetupTriangle& t) {
  std::array<SceneVertex, 3> sv;
  for (int i = 0; i < 3; ++i) {
    sv[size_t(i)].x = Q64{i128(v[size_t(2 * i)]) << (64 - kF)};
    sv[size_t(i)].y = Q64{i128(v[size_t(2 * i + 1)]) << (64 - kF)};
    sv[size_t(i)].z = 0.25 * i;
    sv[size_t(i)].r = uint8_t(kRed[size_t(i)]);
    sv[size_t(i)].g = uint8_t(kGreen[size_t(i)]);
    sv[size_t(i)].b = uint8_t(kBlue[size_t(i)]);
  }
  return setup_triangle(sv, st, {"test", 1}, t);
}

// Random triangles: small, large, thin and sub-pixel, vertices anywhere on the grid
// within the viewport plus a margin of 3 px (kept inside the coordinate range).
std::array<int64_t, 6> random_triangle(std::mt19937_64& rng, const RasterState& st) {
  const int64_t one = int64_t{1} << kF;
  auto coord = [&](int64_t lo_px, int64_t hi_px) {
    return lo_px * one + int64_t(rng() % uint64_t((hi_px - lo_px) * one));
  };
  std::array<int64_t, 6> v{};
  const int kind = int(rng() % 4);
  v[0] = coord(-3, st.fb_width + 3);
  v[1] = coord(-3, st.fb_height + 3);
  const int64_t reach = kind == 0 ? one * 2 : kind == 1 ? one * 12 : one * 40;
  for (int i = 1; i < 3; ++i) {
    v[size_t(2 * i)] = v[0] + int64_t(rng() % uint64_t(2 * reach)) - reach;
    v[size_t(2 * i + 1)] = v[1] + int64_t(rng() % uint64_t(2 * reach)) - reach;
  }
  if (kind == 3) {  // a sliver: the third vertex close to the line through the first two
    v[4] = v[0] + (v[2] - v[0]) * 3 / 7 + int64_t(rng() % 4096) - 2048;
    v[5] = v[1] + (v[3] - v[1]) * 3 / 7 + int64_t(rng() % 4096) - 2048;
  }
  return v;
}

// The brute-force mask: sample s covered <=> centre covered by the triangle moved by -d_s.
std::map<std::pair<int, int>, uint32_t> brute_force_masks(const std::array<int64_t, 6>& v, const RasterState& st) {
  const SamplePattern& p = sample_pattern(st.samples, kF);
  RasterState one = st;
  one.samples = 1;
  std::map<std::pair<int, int>, uint32_t> out;
  for (int s = 0; s < st.samples; ++s) {
    std::array<int64_t, 6> m = v;
    for (int i = 0; i < 3; ++i) {
      m[size_t(2 * i)] -= p.dx[size_t(s)];
      m[size_t(2 * i + 1)] -= p.dy[size_t(s)];
    }
    SetupTriangle t;
    const SetupOutcome o = setup_raw(m, one, t);
    if (o == SetupOutcome::CulledZeroArea) return {};
    // Edges are set up before the bbox clip, so a triangle culled as outside the clip
    // still has its edge equations; every pixel of the clip rectangle is tested.
    const PixelRect clip = one.clip_rect();
    for (int py = clip.y0; py < clip.y1; ++py)
      for (int px = clip.x0; px < clip.x1; ++px)
        if (pixel_covered(t, px, py, kF)) out[{px, py}] |= 1u << s;
  }
  return out;
}

TEST(MsaaCoverage, EveryTraversalMatchesTheTranslatedCentreTest) {
  std::mt19937_64 rng(0x5a3d1e);
  uint64_t pixels = 0, partial = 0;
  for (int S : {2, 4, 8, 16}) {
    for (int k = 0; k < 150; ++k) {
      RasterState st = small_state(S);
      const auto v = random_triangle(rng, st);
      const auto want = brute_force_masks(v, st);
      SetupTriangle t;
      const SetupOutcome o = setup_raw(v, st, t);
      if (o != SetupOutcome::Accepted) {
        EXPECT_TRUE(want.empty()) << "setup culled (" << to_string(o) << ") a triangle that covers samples";
        continue;
      }
      struct M { Traversal method; int tile; };
      for (const M m : {M{Traversal::Tiled, 8}, M{Traversal::Tiled, 2}, M{Traversal::Bbox, 8},
                        M{Traversal::Hierarchical, 8}}) {
        st.traversal = m.method;
        st.tile_size = m.tile;
        st.hier_levels = {16, 4};
        TraversalCounters c;
        std::map<std::pair<int, int>, uint32_t> got;
        traverse(t, traversal_params(st), c, [&](int px, int py, uint32_t mask) {
          EXPECT_NE(mask, 0u);
          EXPECT_TRUE(got.emplace(std::make_pair(px, py), mask).second) << "pixel emitted twice";
        });
        ASSERT_EQ(got, want) << "S=" << S << " triangle " << k << " method " << to_string(m.method) << " tile "
                             << m.tile;
        uint64_t covered = 0, part = 0;
        for (const auto& [px, mask] : got) {
          covered += uint64_t(std::popcount(mask));
          part += mask != t.full_mask();
        }
        EXPECT_EQ(c.samples_covered, covered);
        EXPECT_EQ(c.pixels_partially_covered, part);
        EXPECT_EQ(c.fragments, got.size());
        EXPECT_EQ(c.sample_tests, c.pixel_tests * uint64_t(S));
        pixels += got.size();
        partial += part;
      }
      // The single-pixel function agrees too.
      for (const auto& [px, mask] : want) EXPECT_EQ(pixel_sample_mask(t, px.first, px.second, kF), mask);
    }
  }
  // The scenes exercised what they claim: many pixels, many of them partial.
  EXPECT_GT(pixels, 20000u);
  EXPECT_GT(partial, 5000u);
}

// Barycentric weights from cross products of the vertices (not the edge equations):
// the attribute at raw point (x, y), rounded half up and clamped to [0, 2^bits - 1].
uint32_t attribute_by_cross_products(const SetupTriangle& t, int64_t x, int64_t y, std::array<uint32_t, 3> a,
                                     int bits) {
  auto cross = [&](int i, int j) {  // doubled signed area of (p, v_i, v_j)
    return i128(t.x[size_t(i)] - x) * (t.y[size_t(j)] - y) - i128(t.y[size_t(i)] - y) * (t.x[size_t(j)] - x);
  };
  const i128 w0 = cross(1, 2), w1 = cross(2, 0), w2 = cross(0, 1);
  i128 den = w0 + w1 + w2;  // the doubled signed area
  i128 num = w0 * a[0] + w1 * a[1] + w2 * a[2];
  if (den < 0) den = -den, num = -num;
  // floor((2 num + den) / (2 den)): round half up
  const i128 n2 = 2 * num + den, d2 = 2 * den;
  i128 q = n2 / d2;
  if (n2 % d2 != 0 && n2 < 0) --q;
  return uint32_t(std::clamp<i128>(q, 0, (i128(1) << bits) - 1));
}

TEST(MsaaShading, CentreExtrapolatedAndSsaaAtEachSample) {
  std::mt19937_64 rng(0x77aa);
  uint64_t outside_centres = 0, ssaa_fragments = 0;
  for (int S : {4, 8}) {
    for (int k = 0; k < 150; ++k) {
      RasterState st = small_state(S);
      const auto v = random_triangle(rng, st);
      SetupTriangle t;
      if (setup_raw(v, st, t) != SetupOutcome::Accepted) continue;
      const SamplePattern& p = sample_pattern(S, kF);
      TraversalCounters c;
      traverse(t, traversal_params(st), c, [&](int px, int py, uint32_t mask) {
        // msaa: one fragment, centre attributes.
        t.aa_mode = AaMode::Msaa;
        int n = 0;
        shade_pixel(t, px, py, mask, kF, [&](const Fragment& f) {
          ++n;
          const int64_t cx = t.sample_x(px, kF), cy = t.sample_y(py, kF);
          EXPECT_EQ(f.mask, mask);
          EXPECT_EQ(f.r, attribute_by_cross_products(t, cx, cy, kRed, 8));
          EXPECT_EQ(f.b, attribute_by_cross_products(t, cx, cy, kBlue, 8));
          EXPECT_EQ(f.z, attribute_by_cross_products(t, cx, cy, t.z, t.depth_bits));
          outside_centres += !pixel_covered(t, px, py, kF);
        });
        EXPECT_EQ(n, 1);
        // ssaa: one fragment per covered sample, in sample order, at the sample.
        t.aa_mode = AaMode::Ssaa;
        int next = 0;
        shade_pixel(t, px, py, mask, kF, [&](const Fragment& f) {
          ASSERT_EQ(std::popcount(uint32_t(f.mask)), 1);
          const int s = std::countr_zero(uint32_t(f.mask));
          EXPECT_TRUE((mask >> s) & 1);
          EXPECT_GE(s, next);
          next = s + 1;
          const int64_t sx = t.sample_x(px, kF) + p.dx[size_t(s)], sy = t.sample_y(py, kF) + p.dy[size_t(s)];
          EXPECT_EQ(f.g, attribute_by_cross_products(t, sx, sy, kGreen, 8));
          EXPECT_EQ(f.z, attribute_by_cross_products(t, sx, sy, t.z, t.depth_bits));
          ++ssaa_fragments;
        });
      });
    }
  }
  EXPECT_GT(outside_centres, 500u);  // the extrapolation and clamp were exercised
  EXPECT_GT(ssaa_fragments, 20000u);
}

TEST(MsaaResolve, BoxFilterRoundsHalfUp) {
  Framebuffer fb(2, 1, 4);
  const uint8_t r[4] = {0, 0, 0, 255}, b[4] = {1, 2, 2, 2};
  for (int s = 0; s < 4; ++s) {
    fb.sample(0, 0, s)[0] = r[s];  // 255 / 4 = 63.75 -> 64
    fb.sample(0, 0, s)[1] = 255;   // 255
    fb.sample(0, 0, s)[2] = b[s];  // 7 / 4 = 1.75 -> 2
    fb.sample(1, 0, s)[0] = uint8_t(s < 2 ? 10 : 11);  // 10.5 -> 11 (half up)
  }
  const Framebuffer out = fb.resolve();
  ASSERT_EQ(out.samples, 1);
  EXPECT_EQ(out.pixel(0, 0)[0], 64);
  EXPECT_EQ(out.pixel(0, 0)[1], 255);
  EXPECT_EQ(out.pixel(0, 0)[2], 2);
  EXPECT_EQ(out.pixel(0, 0)[3], 255);
  EXPECT_EQ(out.pixel(1, 0)[0], 11);
  Framebuffer two(1, 1, 2);
  two.sample(0, 0, 0)[0] = 0;
  two.sample(0, 0, 1)[0] = 255;  // 127.5 -> 128
  EXPECT_EQ(two.resolve().pixel(0, 0)[0], 128);
}

// Pixel (0, 0) at 4x has samples at (0.375, 0.125), (0.875, 0.375), (0.125, 0.625),
// (0.625, 0.875) px. A (far, red) covers the 4x4 viewport; B (near, blue) covers x < 0.5
// there: samples 0 and 2. Resolved: red and blue each (2 x 255 + 2) / 4 = 128, in either
// drawing order (depth per sample). One sample: the centre (0.5, 0.5) lies on B's right
// edge, excluded by the top-left rule: red.
TEST(MsaaDepth, PerSampleDepthAndResolveOnAHandWorkedPixel) {
  auto vtx = [](double x, double y, double z, uint8_t r, uint8_t b) { return screen_vertex(x, y, z, r, 0, b); };
  CmdPrimitives a, bb;
  a.vertices = {vtx(-1, -1, 0.8, 255, 0), vtx(9, -1, 0.8, 255, 0), vtx(-1, 9, 0.8, 255, 0)};
  bb.vertices = {vtx(-4, -4, 0.2, 0, 255), vtx(0.5, -4, 0.2, 0, 255), vtx(0.5, 8, 0.2, 0, 255)};
  for (bool a_first : {true, false}) {
    for (int S : {1, 4}) {
      Scene scene;
      scene.commands.push_back({CmdViewport{4, 4}, {"hand", 1}});
      scene.commands.push_back({a_first ? a : bb, {"hand", 2}});
      scene.commands.push_back({a_first ? bb : a, {"hand", 3}});
      RasterState st = raster_state_from_config(Config{});
      st.fb_width = st.fb_height = 4;
      st.samples = S;
      st.depth_func = DepthFunc::Less;
      RenderStats stats;
      const Framebuffer fb = render_scene(scene, st, stats);
      SCOPED_TRACE(std::string(a_first ? "A first" : "B first") + ", S=" + std::to_string(S));
      ASSERT_EQ(fb.samples, 1);
      const uint8_t* p = fb.pixel(0, 0);
      if (S == 4) {
        EXPECT_EQ(p[0], 128);
        EXPECT_EQ(p[2], 128);
      } else {
        EXPECT_EQ(p[0], 255);
        EXPECT_EQ(p[2], 0);
      }
      EXPECT_EQ(fb.pixel(1, 0)[0], 255);
      EXPECT_EQ(fb.pixel(1, 0)[2], 0);
      EXPECT_EQ(stats.color_buffer_bytes, 16u * 4 * uint64_t(S));
      EXPECT_EQ(stats.resolve_bytes, S == 1 ? 0u : 16u * 4 * 4 + 16u * 4);
    }
  }
}

TEST(MsaaConfig, UnsupportedCombinationsAreNamedErrors) {
  Config bad;
  EXPECT_THROW(bad.apply_override("raster.samples=3"), ConfigError);
  auto message = [](std::initializer_list<const char*> sets) -> std::string {
    Config c;
    for (const char* s : sets) c.apply_override(s);
    try {
      c.validate();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({"raster.samples=4", "raster.traversal=scanline"}).find("raster.traversal = scanline"),
            std::string::npos);
  EXPECT_NE(message({"raster.samples=8", "interp.method=dda"}).find("interp.method"), std::string::npos);
  EXPECT_EQ(message({"raster.samples=16", "raster.traversal=hierarchical", "raster.aa_mode=ssaa"}), "");

  // A 2D command with samples > 1 stops with its file:line.
  Scene scene;
  scene.commands.push_back({CmdViewport{8, 8}, {"scene.trace", 1}});
  CmdDraw2d d2;
  d2.keyword = "point";
  scene.commands.push_back({d2, {"scene.trace", 2}});
  RasterState st = small_state(4);
  RenderStats stats;
  try {
    render_scene(scene, st, stats);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.trace:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("raster.samples = 4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim
