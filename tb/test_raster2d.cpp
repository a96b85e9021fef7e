// SPDX-License-Identifier: Apache-2.0
// 2D pixel operations (ref/2d/raster2d.h): blits against a copy-then-write model evaluated
// per destination pixel from a snapshot of the whole framebuffer (random overlapping
// copies in all four directions, random codes, clips and scissors), hand-worked
// overlapping copies, and pattern fills by hand.
#include <gtest/gtest.h>

#include <random>

#include "ref/2d/raster2d.h"
#include "ref/2d/rop3.h"

namespace rastsim {
namespace {

void randomize(Framebuffer& fb, std::mt19937& rng) {
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      uint8_t* p = fb.pixel(x, y);
      for (int c = 0; c < 4; ++c) p[c] = c == 3 ? 255 : uint8_t(rng());
    }
}

// The blit by its definition: every destination pixel inside the destination box, the
// clip and the framebuffer whose source pixel lies inside the source box and the
// framebuffer takes ROP3(P, S from the snapshot, D).
Framebuffer blit_model(const Framebuffer& before, const PixelRect& clip, const Raster2dState& st, int sx, int sy,
                       int dx, int dy, int w, int h) {
  Framebuffer fb = before;
  for (int y = dy; y < dy + h; ++y)
    for (int x = dx; x < dx + w; ++x) {
      const int ux = sx + (x - dx), uy = sy + (y - dy);
      const bool dst_ok = x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1 && x >= 0 && y >= 0 &&
                          x < fb.width && y < fb.height;
      const bool src_ok = ux >= 0 && uy >= 0 && ux < fb.width && uy < fb.height;
      if (!dst_ok || !src_ok) continue;
      const bool pat = st.pattern.solid || ((st.pattern.rows[size_t(y % 8)] >> (7 - x % 8)) & 1);
      for (int c = 0; c < 3; ++c)
        fb.pixel(x, y)[c] = rop3(st.rop3, pat ? st.fg[size_t(c)] : st.bg[size_t(c)], before.pixel(ux, uy)[c],
                                 before.pixel(x, y)[c]);
    }
  return fb;
}

TEST(Raster2d, OverlappingBlitsInAllDirectionsMatchCopyThenWrite) {
  std::mt19937 rng(99);
  for (int i = 0; i < 2000; ++i) {
    Framebuffer fb(24, 20);
    randomize(fb, rng);
    Raster2dState st;
    st.fg = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng())};
    st.bg = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng())};
    st.rop3 = (i % 3 == 0) ? kRopSrcCopy : uint8_t(rng());
    st.pattern.solid = i % 2;
    for (auto& r : st.pattern.rows) r = uint8_t(rng());
    std::uniform_int_distribution<int> pos(-6, 26), size(0, 18), shift(-4, 4);
    const int sx = pos(rng), sy = pos(rng), w = size(rng), h = size(rng);
    const int dx = sx + shift(rng), dy = sy + shift(rng);  // mostly overlapping, every direction
    PixelRect clip{0, 0, 24, 20};
    if (i % 4 == 1) clip = PixelRect{3, 2, 17, 15};  // a scissor
    const Framebuffer want = blit_model(fb, clip, st, sx, sy, dx, dy, w, h);
    blit(fb, clip, st, sx, sy, dx, dy, w, h);
    ASSERT_TRUE(fb.same_color(want)) << "blit " << sx << "," << sy << " -> " << dx << "," << dy << " " << w << "x" << h
                                  << " code " << int(st.rop3);
  }
}

TEST(Raster2d, HandWorkedOverlappingCopies) {
  // One row 0 1 2 3 4 5 (red channel); SRCCOPY of pixels 0..3 one to the right gives
  // 0 0 1 2 3 5, and one to the left (source 1..4) gives 1 2 3 4 4 5.
  auto row = [] {
    Framebuffer fb(6, 1);
    for (int x = 0; x < 6; ++x) fb.pixel(x, 0)[0] = uint8_t(x);
    return fb;
  };
  auto reds = [](const Framebuffer& fb) {
    std::vector<int> r;
    for (int x = 0; x < 6; ++x) r.push_back(fb.pixel(x, 0)[0]);
    return r;
  };
  Raster2dState st;
  st.rop3 = kRopSrcCopy;
  Framebuffer right = row();
  blit(right, {0, 0, 6, 1}, st, 0, 0, 1, 0, 4, 1);
  EXPECT_EQ(reds(right), (std::vector<int>{0, 0, 1, 2, 3, 5}));
  Framebuffer left = row();
  blit(left, {0, 0, 6, 1}, st, 1, 0, 0, 0, 4, 1);
  EXPECT_EQ(reds(left), (std::vector<int>{1, 2, 3, 4, 4, 5}));
}

TEST(Raster2d, PatternFillByHand) {
  // Checkerboard 0xAA / 0x55 rows: pixel (0, 0) is row 0 bit 7 = 1 (foreground), (1, 0)
  // background, (0, 1) row 1 bit 7 = 0 (background); anchored to the screen, so x = 8
  // repeats x = 0.
  Framebuffer fb(16, 2);
  Raster2dState st;
  st.fg = {200, 0, 0};
  st.bg = {0, 0, 50};
  st.rop3 = kRopPatCopy;
  st.pattern.solid = false;
  st.pattern.rows = {0xAA, 0x55, 0xAA, 0x55, 0xAA, 0x55, 0xAA, 0x55};
  EXPECT_EQ(fill_span(fb, {0, 0, 16, 2}, st, 0, -3, 100), 16u);  // clipped to the framebuffer
  EXPECT_EQ(fill_span(fb, {0, 0, 16, 2}, st, 1, 2, 10), 8u);
  EXPECT_EQ(fb.pixel(0, 0)[0], 200);
  EXPECT_EQ(fb.pixel(1, 0)[2], 50);
  EXPECT_EQ(fb.pixel(8, 0)[0], 200);
  EXPECT_EQ(fb.pixel(2, 1)[2], 50);
  EXPECT_EQ(fb.pixel(3, 1)[0], 200);
  EXPECT_EQ(fb.pixel(1, 1)[0], 0);  // outside the span: untouched (clear black)
  EXPECT_EQ(fb.pixel(3, 1)[3], 255);
}

}  // namespace
}  // namespace rastsim
