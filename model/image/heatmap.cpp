// SPDX-License-Identifier: Apache-2.0
#include "image/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "ref/2d/font.h"

namespace rastsim {

namespace {

constexpr int kTextScale = 2;                          // font pixels per glyph pixel
constexpr int kLine = (kFontRows + 2) * kTextScale;     // px per text line
constexpr int kHeader = 3 * kLine + 8;                 // legend strip above the frame, px
constexpr int kBarWidth = 24, kPanel = 150;            // colour bar and its panel, px
constexpr uint8_t kBackground = 24;                    // grey of the panels

void put(Framebuffer& fb, int x, int y, const uint8_t rgb[3]) {
  if (x < 0 || y < 0 || x >= fb.width || y >= fb.height) return;
  uint8_t* p = fb.pixel(x, y);
  p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
}

// Draws `s` (printable ASCII) with its top-left at (x, y), in white.
void text(Framebuffer& fb, int x, int y, const std::string& s) {
  const uint8_t white[3] = {235, 235, 235};
  for (char c : s) {
    if (c < kFontFirstChar || c > kFontLastChar) c = '?';
    const Glyph& g = font_glyph(c);
    for (int r = 0; r < kFontRows; ++r)
      for (int col = 0; col < g.width; ++col)
        if (g.bit(r, col))
          for (int dy = 0; dy < kTextScale; ++dy)
            for (int dx = 0; dx < kTextScale; ++dx) put(fb, x + col * kTextScale + dx, y + r * kTextScale + dy, white);
    x += (g.width + 1) * kTextScale;
  }
}

}  // namespace

void colormap_viridis(double t, uint8_t rgb[3]) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(t, 0.0, 1.0) * double(kStops.size() - 1);
  const size_t i = std::min(size_t(t), kStops.size() - 2);
  const double f = t - double(i);
  for (int c = 0; c < 3; ++c) rgb[c] = uint8_t(std::lround(kStops[i][c] * (1 - f) + kStops[i + 1][c] * f));
}

Framebuffer draw_heatmap(const Framebuffer& frame, const TileGrid& g, const std::string& title) {
  const int scale = std::max(1, 640 / std::max(1, frame.width));  // whole factor, >= 640 px wide
  const int fw = frame.width * scale, fh = frame.height * scale;
  Framebuffer out(fw + kPanel, std::max(fh, 8 * kLine) + kHeader);
  out.clear_color(kBackground, kBackground, kBackground);
  const uint64_t max = g.cycles.empty() ? 0 : *std::max_element(g.cycles.begin(), g.cycles.end());
  const uint64_t total = std::accumulate(g.cycles.begin(), g.cycles.end(), uint64_t{0});

  // The frame, dimmed, with the costly tiles painted over it.
  for (int y = 0; y < fh; ++y)
    for (int x = 0; x < fw; ++x) {
      const int px = x / scale, py = y / scale;
      const uint8_t* src = frame.pixel(px, py);
      double rgb[3] = {0.35 * src[0], 0.35 * src[1], 0.35 * src[2]};
      const size_t tile = size_t(py / g.tile_size) * size_t(g.tiles_x) + size_t(px / g.tile_size);
      if (tile < g.cycles.size() && g.cycles[tile] > 0) {  // zero-cost tiles stay clear
        uint8_t c[3];
        colormap_viridis(double(g.cycles[tile]) / double(max), c);
        for (int k = 0; k < 3; ++k) rgb[k] = 0.35 * rgb[k] + 0.65 * c[k];
      }
      const uint8_t v[3] = {uint8_t(std::lround(rgb[0])), uint8_t(std::lround(rgb[1])), uint8_t(std::lround(rgb[2]))};
      put(out, x, y + kHeader, v);
    }

  // Legend: what is counted, then the scale.
  text(out, 6, 4, title);
  text(out, 6, 4 + kLine,
       std::to_string(g.tile_size) + "x" + std::to_string(g.tile_size) + " px tiles; max " + std::to_string(max) +
           " cycles/tile, total " + std::to_string(total));
  text(out, 6, 4 + 2 * kLine, "clear = 0 cycles; colour linear from 0 to max");

  // Colour bar: max at the top, 0 at the bottom, five labelled ticks.
  const int bx = fw + 12, by0 = kHeader + kLine / 2, by1 = kHeader + std::max(fh, 8 * kLine) - kLine;
  for (int y = by0; y <= by1; ++y) {
    uint8_t c[3];
    colormap_viridis(double(by1 - y) / double(by1 - by0), c);
    for (int x = bx; x < bx + kBarWidth; ++x) put(out, x, y, c);
  }
  const uint8_t tick[3] = {235, 235, 235};
  for (int i = 0; i <= 4; ++i) {
    const int y = by1 - (by1 - by0) * i / 4;
    for (int x = bx + kBarWidth; x < bx + kBarWidth + 3; ++x) put(out, x, y, tick);
    text(out, bx + kBarWidth + 10, y - kFontRows * kTextScale / 2, std::to_string(max * uint64_t(i) / 4));
  }
  text(out, bx, kHeader - kLine, "cycles");  // the bar's unit, above it
  return out;
}

}  // namespace rastsim
