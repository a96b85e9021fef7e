// SPDX-License-Identifier: Apache-2.0
// Text as the notes draw it, "rectangle fill with character bitmap pattern"
// (docs/2d-text.md): each character is a rectangle fill of its cell, the glyph's bitmap
// deciding pixel by pixel what is drawn. The front end hands the engine that fill as
// runs along each row: ink runs take the P operand (the current pattern, the plain
// colour under `pattern solid`), paper runs are skipped, or painted with `bgcolor`
// when the font is opaque.
//
// Cell of one character, in font units (1 unit = `scale` x `scale` screen pixels):
// - kFontRows rows; columns [0, advance). The glyph sits at column `offset` (0 for
//   proportional spacing, centred in the kFontMaxWidth columns for fixed spacing).
// - bold (double strike): ink = glyph | glyph one column to the right; the glyph is
//   one column wider. Each pixel is still written once, so a ROP3 that reads D (XOR)
//   does not cancel the two strikes.
// - advance = glyph width + 1 (proportional) or kFontMaxWidth + 1 (fixed), +1 bold.
// - underline: row kUnderlineRow is ink across the whole advance, so it runs on
//   unbroken from character to character.
#pragma once

#include <cstdint>
#include <string_view>

#include "ref/2d/font.h"
#include "ref/scene.h"

namespace rastsim {

constexpr int kUnderlineRow = kFontRows - 1;

// One character's cell with the style applied.
struct TextCell {
  int advance = 0;  // font units
  int offset = 0;   // glyph's column 0 within the cell
  const Glyph* glyph = nullptr;
  bool bold = false, underline = false;
  // Ink at cell row r (0..kFontRows-1), column c (0..advance-1).
  bool ink(int r, int c) const {
    if (underline && r == kUnderlineRow) return true;
    const int gc = c - offset;
    return glyph->bit(r, gc) || (bold && glyph->bit(r, gc - 1));
  }
};

TextCell text_cell(char c, const TextStyle& style);

// Width of the whole string in screen pixels: the sum of the advances times the scale.
int64_t text_width(std::string_view str, const TextStyle& style);

// Calls fn(y, x0, x1, ink) for each run of equal pixels of the text whose first cell's
// top-left pixel is (x, y): character by character, then row by row (each font row
// `scale` times), runs left to right; paper runs only when style.opaque. The runs are
// not clipped. `str` holds printable ASCII only.
template <class Fn>
void text_runs(int x, int y, std::string_view str, const TextStyle& style, Fn&& fn) {
  const int s = style.scale;
  int64_t cx = x;  // cell's left edge, screen pixels
  for (char ch : str) {
    const TextCell cell = text_cell(ch, style);
    for (int r = 0; r < kFontRows; ++r) {
      for (int c0 = 0; c0 < cell.advance;) {
        const bool ink = cell.ink(r, c0);
        int c1 = c0 + 1;
        while (c1 < cell.advance && cell.ink(r, c1) == ink) ++c1;
        if (ink || style.opaque)
          for (int k = 0; k < s; ++k) fn(int(int64_t(y) + int64_t(r) * s + k), cx + int64_t(c0) * s, cx + int64_t(c1) * s, ink);
        c0 = c1;
      }
    }
    cx += int64_t(cell.advance) * s;
  }
}

}  // namespace rastsim
