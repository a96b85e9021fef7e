// SPDX-License-Identifier: Apache-2.0
// Text and the bitmap font (docs/2d-text.md) through the reference pipeline:
// - the font's own promises (widths, descenders, every glyph distinct and inked);
// - a hand-worked picture of "Hi" in fixed and proportional spacing;
// - random strings and styles against a per-pixel evaluation of the stated cell rules
//   (written here again from the doc, pixel by pixel, not run by run), drawn with
//   PATINVERT so that a pixel written twice would cancel;
// - the trace commands' escapes and their file:line errors.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <set>

#include "scene_test.h"
#include "config/raster_state_config.h"
#include "ref/2d/font.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

Framebuffer render(const std::string& text, const std::string& set = "") {
  Config cfg;
  cfg.apply_override("display.width=64");
  cfg.apply_override("display.height=48");
  if (!set.empty()) cfg.apply_override(set);
  RenderStats stats;
  return render_scene(parse_trace(text, "t.trace"), raster_state_from_config(cfg), stats);
}

// The picture of the framebuffer's top-left w x h pixels: '#' where the red channel is
// 255, '.' elsewhere.
std::vector<std::string> picture(const Framebuffer& fb, int w, int h) {
  std::vector<std::string> rows;
  for (int y = 0; y < h; ++y) {
    std::string row;
    for (int x = 0; x < w; ++x) row += fb.pixel(x, y)[0] == 255 ? '#' : '.';
    rows.push_back(row);
  }
  return rows;
}

TEST(Font, EveryPrintableCharacterHasADistinctGlyph) {
  std::set<std::pair<int, std::array<uint8_t, kFontRows>>> seen;
  const std::string descenders = "gjpqy,;_";
  for (int c = kFontFirstChar; c <= kFontLastChar; ++c) {
    SCOPED_TRACE(std::string(1, char(c)));
    const Glyph& g = font_glyph(char(c));
    EXPECT_GE(g.width, 1);
    EXPECT_LE(g.width, kFontMaxWidth);
    int ink = 0;
    for (int r = 0; r < kFontRows; ++r) {
      EXPECT_EQ(g.rows[size_t(r)] & (0xFF >> g.width), 0) << "bits past the width, row " << r;
      for (int col = 0; col < g.width; ++col) ink += g.bit(r, col);
      if (r >= 7 && descenders.find(char(c)) == std::string::npos) {
        EXPECT_EQ(g.rows[size_t(r)], 0) << "row " << r;
      }
    }
    EXPECT_EQ(ink == 0, c == ' ');
    EXPECT_TRUE(seen.insert({g.width, g.rows}).second) << "same bitmap as an earlier glyph";
  }
}

// Worked by hand from the pictures in model/ref/2d/font.cpp and the cell rules: fixed
// spacing puts 'H' (5 wide) at columns 0..4 of a 6-column cell and 'i' (1 wide) at
// column (5 - 1) / 2 = 2 of the next; proportional gives 'i' the columns right after
// H's one spacing column.
TEST(Text, HandWorkedHiFixedAndProportional) {
  const std::vector<std::string> fixed = {
      "#...#...#...", "#...#.......", "#...#...#...", "#####...#...", "#...#...#...",
      "#...#...#...", "#...#...#...", "............", "............", "............",
  };
  EXPECT_EQ(picture(render("color 255 255 255\ntext 0 0 Hi\n"), 12, 10), fixed);
  const std::vector<std::string> proportional = {
      "#...#.#.", "#...#...", "#...#.#.", "#####.#.", "#...#.#.", "#...#.#.", "#...#.#.", "........",
      "........", "........",
  };
  EXPECT_EQ(picture(render("font 1 proportional\ntext 0 0 Hi\n"), 8, 10), proportional);
  // Scale 2, underlined: every font pixel is 2 x 2, and row 8 (screen rows 16, 17) is
  // ink across both cells, spacing columns included.
  const auto big = picture(render("font 2 underline proportional\ntext 0 0 Hi\n"), 18, 18);
  EXPECT_EQ(big[0], "##......##..##....");
  EXPECT_EQ(big[3], "##......##........");  // font row 1: the dot of 'i' is row 0 only
  EXPECT_EQ(big[7], "##########..##....");  // font row 3: H's bar
  EXPECT_EQ(big[16], "################..");
  EXPECT_EQ(big[17], "################..");
}

// The rules of docs/2d-text.md, pixel by pixel.
struct Expected {
  int x0, y0;
  std::string str;
  TextStyle st;
  bool ink_at(int x, int y, bool& in_cell) const {
    in_cell = false;
    const int s = st.scale;
    if (y < y0 || y >= y0 + kFontRows * s) return false;
    const int fy = (y - y0) / s;
    int cell_x = x0;
    for (char c : str) {
      const Glyph& g = font_glyph(c);
      const int bold = st.bold ? 1 : 0;
      const int advance = (st.proportional ? g.width : kFontMaxWidth) + bold + 1;
      const int offset = st.proportional ? 0 : (kFontMaxWidth - g.width) / 2;
      if (x >= cell_x && x < cell_x + advance * s) {
        in_cell = true;
        const int fx = (x - cell_x) / s - offset;
        if (st.underline && fy == kFontRows - 1) return true;
        return g.bit(fy, fx) || (st.bold && g.bit(fy, fx - 1));
      }
      cell_x += advance * s;
    }
    return false;
  }
};

TEST(Text, RandomStringsMatchThePerPixelRule) {
  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int trial = 0; trial < 300; ++trial) {
    Expected e;
    e.x0 = pick(-20, 40);
    e.y0 = pick(-20, 40);
    e.st.scale = pick(1, 3);
    e.st.bold = pick(0, 1);
    e.st.underline = pick(0, 1);
    e.st.proportional = pick(0, 1);
    e.st.opaque = pick(0, 1);
    const int n = pick(1, 8);
    for (int i = 0; i < n; ++i) {
      char c = char(pick(kFontFirstChar, kFontLastChar));
      if (c == '#' || c == '\\') c = 'x';  // these two need escapes: tested separately
      if (c == ' ' && (i == 0 || i == n - 1)) c = 'y';  // blanks at the ends are not part of it
      e.str += c;
    }
    std::string font = "font " + std::to_string(e.st.scale) + (e.st.bold ? " bold" : "") +
                       (e.st.underline ? " underline" : "") + (e.st.proportional ? " proportional" : " fixed") +
                       (e.st.opaque ? " opaque" : " transparent");
    // Cleared to 0, drawn with PATINVERT (P xor D): ink 200, paper 100 where opaque, and
    // a pixel written twice would read back 0. The scissor clips a corner.
    const std::string trace = "viewport 64 48\nscissor 3 2 50 40\nclear 0 0 0\ncolor 200 200 200\n"
                              "bgcolor 100 100 100\nrop3 5A\n" + font + "\ntext " + std::to_string(e.x0) + " " +
                              std::to_string(e.y0) + " " + e.str + "\n";
    SCOPED_TRACE(trace);
    const Framebuffer fb = render(trace);
    int wrong = 0;
    for (int y = 0; y < fb.height; ++y)
      for (int x = 0; x < fb.width; ++x) {
        bool in_cell = false;
        const bool ink = e.ink_at(x, y, in_cell);
        const bool clipped = x < 3 || x >= 53 || y < 2 || y >= 42;
        const int want = clipped || !in_cell ? 0 : ink ? 200 : e.st.opaque ? 100 : 0;
        if (fb.pixel(x, y)[0] != want && wrong++ < 3)
          ADD_FAILURE() << "pixel (" << x << ", " << y << ") is " << int(fb.pixel(x, y)[0]) << ", want " << want;
      }
    ASSERT_EQ(wrong, 0);
  }
}

TEST(Text, EscapesAndBlanksInsideTheString) {
  // "a#b" and "\" via escapes; inner blanks kept, outer ones not.
  const Scene s = parse_trace("text 1 2   a\\x23b  \\\\ z  # comment\n", "t.trace");
  const auto& t = std::get<Draw2dText>(std::get<CmdDraw2d>(s.commands.at(0).body).shape);
  EXPECT_EQ(t.str, "a#b  \\ z");
  EXPECT_EQ(t.x, 1);
  EXPECT_EQ(t.y, 2);
}

TEST(Text, ErrorsNameTheLine) {
  struct Case {
    const char* text;
    int line;
    const char* phrase;
  };
  const Case cases[] = {
      {"text 1 2\n", 1, "'text' takes x y STRING"},
      {"clear 0 0 0\ntext 1.5 2 a\n", 2, "text x '1.5' is not an integer"},
      {"text 1 2 caf\xc3\xa9\n", 1, "text character 4 of 'caf\\xc3\\xa9': not printable ASCII"},
      {"text 1 2 a\\x07\n", 1, "not printable ASCII"},
      {"text 1 2 a\\qb\n", 1, "a backslash starts"},
      {"text 1 2 a\\x4\n", 1, "a backslash starts"},
      {"font 0\n", 1, "font scale 0 is outside 1..16"},
      {"font\n", 1, "'font' takes SCALE"},
      {"font 2 italic\n", 1, "font attribute 'italic' is not one of"},
      {"rop3 CC\ntext 0 0 a\n", 2, "reads the source (S)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_TRUE(scene_test::SceneFails([&] { parse_trace(c.text, "t.trace"); },
                                       "t.trace:" + std::to_string(c.line) + ":", c.phrase));
  }
}

}  // namespace
}  // namespace rastsim
