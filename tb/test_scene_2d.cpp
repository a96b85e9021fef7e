// SPDX-License-Identifier: Apache-2.0
// The 2D commands of traces (docs/trace-format.md) through the reference pipeline:
// errors name file:line and stop before drawing; hand-counted pixels of rects, points,
// lines and blits; quads draw exactly the pixels of their two triangles.
#include <gtest/gtest.h>

#include <functional>

#include "scene_test.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

using scene_test::SceneFails;

Scene parse(const std::string& text) { return parse_trace(text, "t.trace"); }

Framebuffer render(const std::string& text, RenderStats& stats, const std::string& set = "") {
  Config cfg;
  if (!set.empty()) cfg.apply_override(set);
  return render_scene(parse(text), raster_state_from_config(cfg), stats);
}

int count_color(const Framebuffer& fb, uint8_t r, uint8_t g, uint8_t b) {
  int n = 0;
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const uint8_t* p = fb.pixel(x, y);
      n += p[0] == r && p[1] == g && p[2] == b;
    }
  return n;
}

TEST(Scene2d, ErrorsNameTheLine) {
  struct Case {
    const char* text;
    int line;
    const char* phrase;
  };
  const Case cases[] = {
      {"rect 1 2 3\n", 1, "'rect' takes 4 arguments"},
      {"clear 0 0 0\nrect 1 2 -3 4\n", 2, "rect width -3 is outside 0..16384"},
      {"circle 1 2 3 hollow\n", 1, "'circle' takes 3 arguments"},
      {"pattern 0102\n", 1, "is not 16 hex digits"},
      {"pattern 0102030405060G08\n", 1, "non-hex digit"},
      {"rop3 F\n", 1, "is not 2 hex digits"},
      {"rop3 CC\nrect 0 0 4 4\n", 2, "reads the source (S)"},
      {"point_size 0\n", 1, "point size 0 is outside 1..256"},
      {"line 1 2 3\n", 1, "'line' takes 4 arguments"},
      {"lines\nv 1 1\nv 2 2\nv 3 3\nend\n", 1, "needs an even number"},
      {"polygon\nv 1 1\nv 2 2\nend\n", 1, "needs at least 3"},
      {"quads\nv 1 1\nv 2 2\nv 3 3\nend\n", 1, "a multiple of 4"},
      {"linestrip\nv 1 1 0 255 0 0\nend\n", 2, "takes 2 numbers (x y)"},
      {"blit 0 0 1 1 2\n", 1, "'blit' takes 6 arguments"},
      {"polygon\nv 1 1\nrect 0 0 1 1\n", 3, "inside the 'polygon'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_TRUE(SceneFails([&] { parse(c.text); }, "t.trace:" + std::to_string(c.line) + ":", c.phrase));
  }
}

TEST(Scene2d, OutOfRangeCoordinateIsReportedOrCulled) {
  RenderStats st;
  EXPECT_TRUE(SceneFails([&] { render("line 0 0 100000 5\n", st); }, "t.trace:1:", "outside raster.coord_format"));
  RenderStats culled;
  render("line 0 0 100000 5\nrect 0 0 2 2\n", culled, "raster.out_of_range=cull");
  EXPECT_EQ(culled.draw2d.primitives_culled, 1u);
  EXPECT_EQ(culled.draw2d.primitives, 1u);
  EXPECT_EQ(culled.draw2d.pixels, 4u);
}

TEST(Scene2d, HandCountedPixels) {
  RenderStats st;
  // A 5x3 rect, a 2x2 point, a blit of the rect's 2x2 corner; clipped by a scissor.
  const Framebuffer fb = render(
      "color 255 0 0\nrect 2 2 5 3\n"             // 15 red pixels
      "color 0 255 0\npoint_size 2\npoint 20 20\n"  // 2x2 green around the corner (20, 20)
      "rop3 CC\nblit 2 2 40 40 2 2\n"               // 4 red copies
      "rop3 F0\nscissor 100 100 4 4\ncolor 0 0 255\nrect 90 90 20 20\n",  // 16 blue inside the scissor
      st);
  EXPECT_EQ(count_color(fb, 255, 0, 0), 19);
  EXPECT_EQ(count_color(fb, 0, 255, 0), 4);
  EXPECT_EQ(count_color(fb, 0, 0, 255), 16);
  EXPECT_EQ(st.draw2d.pixels, 15u + 4u + 4u + 16u);
  EXPECT_EQ(st.draw2d.primitives, 4u);
}

TEST(Scene2d, LineMethodsFromTheConfig) {
  // (0.5, 0.5) to (8.5, 0.5), centre to centre: the diamond rule draws 8 pixels (not
  // the last), the index methods 9 (both ends).
  for (const char* m : {"diamond", "bresenham", "midpoint", "dda"}) {
    RenderStats st;
    render("line 0.5 0.5 8.5 0.5\n", st, std::string("line.method=") + m);
    EXPECT_EQ(st.draw2d.pixels, std::string(m) == "diamond" ? 8u : 9u) << m;
  }
  // A strip through (8.5, 0.5) draws that pixel once with the diamond rule.
  RenderStats strip;
  render("linestrip\nv 0.5 0.5\nv 8.5 0.5\nv 8.5 6.5\nend\n", strip);
  EXPECT_EQ(strip.draw2d.pixels, 8u + 6u);
}

TEST(Scene2d, QuadsDrawTheirTwoTriangles) {
  const std::string quad = "quads\nv 10 10\nv 50 12\nv 47 40\nv 12 44\nend\n";
  const std::string tris = "tri 10 10 50 12 47 40\ntri 10 10 47 40 12 44\n";
  RenderStats a, b;
  EXPECT_EQ(render(quad, a).color_crc32(), render(tris, b).color_crc32());
  EXPECT_EQ(a.traversal.fragments, b.traversal.fragments);
  EXPECT_GT(a.traversal.fragments, 900u);
  // Quad strip quad (v0, v1, v3, v2) keeps its winding: culled back faces stay culled.
  RenderStats c, d;
  render("quadstrip\nv 10 10\nv 10 40\nv 40 10\nv 40 40\nend\n", c, "raster.cull=back");
  render("quadstrip\nv 10 10\nv 40 10\nv 10 40\nv 40 40\nend\n", d, "raster.cull=back");
  EXPECT_EQ(c.traversal.fragments + d.traversal.fragments, 900u);  // one winding is culled
  EXPECT_TRUE(c.traversal.fragments == 0 || d.traversal.fragments == 0);
}

}  // namespace
}  // namespace rastsim
