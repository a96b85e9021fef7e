// SPDX-License-Identifier: Apache-2.0
// The 2D engine's bitmap font (docs/2d-text.md): "rastsim 5x7", authored for this
// project under its Apache-2.0 licence, printable ASCII 0x20..0x7E.
//
// - A glyph is 1..5 columns wide and kFontRows = 9 rows tall: capitals and digits fill
//   rows 0..6 (the baseline is below row 6), lower case has its x-height at rows 2..6,
//   descenders (g j p q y , ;) reach rows 7..8.
// - Row bits are stored like a pattern row: bit 7 is the leftmost column, so column c
//   is bit (7 - c); bits past the glyph's width are 0.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace rastsim {

constexpr int kFontRows = 9;       // rows of a glyph cell
constexpr int kFontMaxWidth = 5;   // widest glyph, columns
constexpr int kFontFirstChar = 0x20, kFontLastChar = 0x7E;

struct Glyph {
  int width = 0;                          // columns, 1..kFontMaxWidth
  std::array<uint8_t, kFontRows> rows{};  // bit 7 = column 0
  bool bit(int row, int col) const { return col >= 0 && col < width && (rows[size_t(row)] >> (7 - col) & 1); }
};

// The glyph of a printable ASCII character (kFontFirstChar..kFontLastChar). Anything
// else is a precondition violation (the trace parser rejects it with file:line).
const Glyph& font_glyph(char c);

}  // namespace rastsim
