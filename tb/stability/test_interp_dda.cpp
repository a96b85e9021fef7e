// SPDX-License-Identifier: Apache-2.0
// Interpolation (docs/stability.md, "Interpolation"): the span DDA of interp.method =
// "dda" (ref/interpolate.h) against exact rational interpolation.
//
// Span search: ramps over a span of n pixels, v(k) = A + k (B - A) / n for k = 0..n, as a
// triangle's span presents them (exact start num0 / den, exact step dnum / den); the
// golden is v(k) rounded half up, in integers (div_round). Ramps: 0 -> M, M -> 0 and
// (M/2 + 1/3) -> 0 (a start between integers), M = 2^bits - 1, for colour (8 bits) and
// depth (24 bits). For n = 1, 2, ... up to 4096 (the largest viewport side of the shipped
// configs is 1920): the first n at which some ramp's DDA output differs from the golden,
// and the first at which it differs by more than 1 LSB.
// Scene figures: the torus through render_scene with the dda method, max and mean error
// of every fragment's colour and depth against interpolate_plane (stats keys
// max_attr_error_lsb, mean_attr_error_lsb, max_depth_error_lsb).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"
#include "stability/doc_table.h"

namespace rastsim {
namespace {

constexpr int kSpanCap = 4096;

struct SpanFound { int64_t first_diff = 0, first_over_one = 0; };

SpanFound span_search(InterpArith arith, int frac_bits, int bits) {
  const i128 M = (i128(1) << bits) - 1;
  SpanFound f;
  for (int64_t n = 1; n <= kSpanCap && !f.first_over_one; ++n) {
    struct Ramp { i128 num0, dnum, den; };
    const Ramp ramps[] = {{0, M, n}, {M * n, -M, n}, {(3 * (M / 2) + 1) * n, -(3 * (M / 2) + 1), 3 * n}};
    std::vector<uint32_t> got_all;
    for (const Ramp& r : ramps) {
      dda_span_values(r.num0, r.dnum, r.den, n, arith, frac_bits, bits, got_all);
      for (int64_t k = 0; k <= n; ++k) {
        const i128 want = div_round(r.num0 + k * r.dnum, r.den, Rounding::HalfUp);
        const i128 got = got_all[size_t(k)];
        const i128 err = got > want ? got - want : want - got;
        if (err >= 1 && !f.first_diff) f.first_diff = n;
        if (err > 1 && !f.first_over_one) f.first_over_one = n;
      }
    }
  }
  return f;
}

std::string fig(int64_t n) { return n ? std::to_string(n) : "none up to " + std::to_string(kSpanCap); }

struct SpanCase { const char* row; InterpArith arith; int frac_bits; int bits; };
void PrintTo(const SpanCase& c, std::ostream* os) { *os << c.row; }

class InterpDdaSpan : public ::testing::TestWithParam<SpanCase> {};

TEST_P(InterpDdaSpan, FirstErrorMatchesTheDoc) {
  const SpanCase c = GetParam();
  const SpanFound f = span_search(c.arith, c.frac_bits, c.bits);
  std::printf("| %s | %s | %s |\n", c.row, fig(f.first_diff).c_str(), fig(f.first_over_one).c_str());
  const testing::DocRow row = testing::doc_row("Interpolation", c.row);
  ASSERT_GE(row.size(), 3u);
  EXPECT_EQ(fig(f.first_diff), row[1]) << "the figure moved: update docs/stability.md and say why";
  EXPECT_EQ(fig(f.first_over_one), row[2]) << "the figure moved: update docs/stability.md and say why";
}

INSTANTIATE_TEST_SUITE_P(Arith, InterpDdaSpan,
                         ::testing::Values(SpanCase{"f32, colour 8 bits", InterpArith::F32, 0, 8},
                                           SpanCase{"f32, depth 24 bits", InterpArith::F32, 0, 24},
                                           SpanCase{"fixed 16, colour 8 bits", InterpArith::Fixed, 16, 8},
                                           SpanCase{"fixed 16, depth 24 bits", InterpArith::Fixed, 16, 24},
                                           SpanCase{"fixed 8, colour 8 bits", InterpArith::Fixed, 8, 8}),
                         [](const auto& info) {
                           std::string n;
                           for (char ch : std::string(info.param.row))
                             if (std::isalnum(static_cast<unsigned char>(ch))) n += ch;
                           return n;
                         });

// Max and mean output error (LSBs, against the golden) over the three ramps and every
// k = 0..n, by span length n: the doc's second "Interpolation" table.
TEST(InterpDdaSpan, ErrorBySpanLengthMatchesTheDoc) {
  struct Col { InterpArith arith; int frac_bits, bits; };
  const Col cols[] = {{InterpArith::F32, 0, 8}, {InterpArith::F32, 0, 24}, {InterpArith::Fixed, 16, 8},
                      {InterpArith::Fixed, 16, 24}};
  for (int64_t n : {3, 10, 30, 100, 300, 1000, 3000}) {
    std::string line = "| " + std::to_string(n);
    std::vector<std::string> cells;
    for (size_t c = 0; c < 4; ++c) {
      const i128 M = (i128(1) << cols[c].bits) - 1;
      const i128 ramps[3][3] = {{0, M, n}, {M * n, -M, n}, {(3 * (M / 2) + 1) * n, -(3 * (M / 2) + 1), 3 * n}};
      i128 max_err = 0, sum = 0, count = 0;
      std::vector<uint32_t> got_all;
      for (const auto& r : ramps) {
        dda_span_values(r[0], r[1], r[2], n, cols[c].arith, cols[c].frac_bits, cols[c].bits, got_all);
        for (int64_t k = 0; k <= n; ++k) {
          const i128 w = div_round(r[0] + k * r[1], r[2], Rounding::HalfUp);
          const i128 g = got_all[size_t(k)];
          const i128 e = g > w ? g - w : w - g;
          max_err = std::max(max_err, e);
          sum += e;
          ++count;
        }
      }
      char cell[48];
      std::snprintf(cell, sizeof cell, "%s / %.3f", to_string(max_err).c_str(), double(sum) / double(count));
      line += std::string(" | ") + cell;
      cells.push_back(cell);
    }
    std::printf("%s |\n", line.c_str());
    const testing::DocRow want = testing::doc_row("Interpolation", std::to_string(n), 1);
    ASSERT_EQ(want.size(), 5u);
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(cells[c], want[c + 1]) << "n = " << n << ", column " << c + 1;
  }
}

// The DDA itself, hand-worked: a ramp 0 -> 255 over 3 pixels has the exact step 85, so
// both arithmetics are exact; 0 -> 255 over 7 pixels (step 36.43) in 2-bit fixed point
// rounds the step to 36.5 (146 / 4, ties to even of 145.71 -> 146): at k = 7 the DDA
// gives 255.5 -> 256, clamped to 255; at k = 6, 219 -> 219 vs exact 218.57 -> 219.
TEST(InterpDdaGolden, HandWorkedRamps) {
  for (int64_t k = 0; k <= 3; ++k) {
    EXPECT_EQ(dda_span_value(0, 255, 3, k, InterpArith::Fixed, 4, 8), 85 * k);
    EXPECT_EQ(dda_span_value(0, 255, 3, k, InterpArith::F32, 0, 8), 85 * k);
  }
  EXPECT_EQ(dda_span_value(0, 255, 7, 7, InterpArith::Fixed, 2, 8), 255u);
  EXPECT_EQ(dda_span_value(0, 255, 7, 6, InterpArith::Fixed, 2, 8), 219u);
  EXPECT_EQ(dda_span_value(0, 255, 7, 1, InterpArith::Fixed, 2, 8), 37u);  // 36.5 rounds half up; exact 36.43 -> 36
  // The per-pixel value (closed form for fixed) equals the walked span at every step.
  for (InterpArith a : {InterpArith::F32, InterpArith::Fixed}) {
    std::vector<uint32_t> all;
    dda_span_values(3 * 1000 + 1, -(3 * 16000000 + 7), 3 * 997, 997, a, 12, 24, all);
    for (int64_t k = 0; k <= 997; k += 37)
      EXPECT_EQ(dda_span_value(3 * 1000 + 1, -(3 * 16000000 + 7), 3 * 997, k, a, 12, 24), all[size_t(k)]);
  }
}

RasterState torus_state(const char* arith, int tile) {
  Config cfg;
  cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/default.toml");
  cfg.apply_override("interp.method=dda");
  cfg.apply_override(std::string("interp.dda_arith=") + arith);
  cfg.apply_override("raster.tile_size=" + std::to_string(tile));
  return raster_state_from_config(cfg);
}

TEST(InterpDdaScene, TorusErrorMatchesTheDoc) {
  const Scene torus = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace", ObjPlacement{});
  for (const char* arith : {"f32", "fixed"}) {
    SCOPED_TRACE(arith);
    RenderStats s;
    render_scene(torus, torus_state(arith, 16), s);
    char mean[32], dmean[32];
    std::snprintf(mean, sizeof mean, "%.4f", double(s.attr_error_sum) / double(3 * s.traversal.fragments));
    std::snprintf(dmean, sizeof dmean, "%.4f", double(s.depth_error_sum) / double(s.traversal.fragments));
    const std::string key = std::string("torus, ") + arith;
    std::printf("| %s | %u | %s | %u | %s |\n", key.c_str(), s.max_attr_error_lsb, mean, s.max_depth_error_lsb, dmean);
    const testing::DocRow row = testing::doc_row("Interpolation", key, 2);
    ASSERT_GE(row.size(), 5u);
    EXPECT_EQ(std::to_string(s.max_attr_error_lsb), row[1]);
    EXPECT_EQ(mean, row[2]);
    EXPECT_EQ(std::to_string(s.max_depth_error_lsb), row[3]);
    EXPECT_EQ(dmean, row[4]);
  }
}

// A pixel's DDA value depends on its span, not on the order traversal delivers it: the
// same image and fragment values at every tile size.
TEST(InterpDdaScene, IndependentOfTileSize) {
  const Scene torus = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace", ObjPlacement{});
  for (const char* arith : {"f32", "fixed"}) {
    uint32_t crc0 = 0;
    for (int tile : {2, 16, 128}) {
      RenderStats s;
      const Framebuffer fb = render_scene(torus, torus_state(arith, tile), s);
      if (tile == 2) crc0 = fb.color_crc32();
      EXPECT_EQ(fb.color_crc32(), crc0) << arith << " tile " << tile;
    }
  }
}

}  // namespace
}  // namespace rastsim
