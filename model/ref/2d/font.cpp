// SPDX-License-Identifier: Apache-2.0
// "rastsim 5x7", the 2D engine's bitmap font: authored for this project (Apache-2.0),
// printable ASCII 0x20..0x7E. The glyphs are kept as pictures so that a reader can
// review and change them; font_glyph() turns them into row bits once, on first use.
//
// Picture format: a header "@HH c" (HH = the character code in hex, c = the character
// for the reader), then 7 to 9 rows of '#' (ink) and '.' (paper), all of one width
// 1..kFontMaxWidth. Rows not given are paper; only descenders use rows 7 and 8.
#include "ref/2d/font.h"

#include <stdexcept>
#include <string>
#include <string_view>

namespace rastsim {

namespace {

constexpr std::string_view kFontPictures = R"font(
@20 space
...
...
...
...
...
...
...
@21 !
#
#
#
#
#
.
#
@22 "
#.#
#.#
...
...
...
...
...
@23 #
.#.#.
.#.#.
#####
.#.#.
#####
.#.#.
.#.#.
@24 $
..#..
.####
#.#..
.###.
..#.#
####.
..#..
@25 %
##...
##..#
...#.
..#..
.#...
#..##
...##
@26 &
.##..
#..#.
#.#..
.#...
#.#.#
#..#.
.##.#
@27 '
#
#
.
.
.
.
.
@28 (
..#
.#.
#..
#..
#..
.#.
..#
@29 )
#..
.#.
..#
..#
..#
.#.
#..
@2A *
.....
..#..
#.#.#
.###.
#.#.#
..#..
.....
@2B +
.....
..#..
..#..
#####
..#..
..#..
.....
@2C ,
..
..
..
..
..
##
.#
#.
@2D -
....
....
....
####
....
....
....
@2E .
..
..
..
..
..
##
##
@2F /
.....
....#
...#.
..#..
.#...
#....
.....
@30 0
.###.
#...#
#..##
#.#.#
##..#
#...#
.###.
@31 1
.#.
##.
.#.
.#.
.#.
.#.
###
@32 2
.###.
#...#
....#
...#.
..#..
.#...
#####
@33 3
#####
...#.
..#..
...#.
....#
#...#
.###.
@34 4
...#.
..##.
.#.#.
#..#.
#####
...#.
...#.
@35 5
#####
#....
####.
....#
....#
#...#
.###.
@36 6
..##.
.#...
#....
####.
#...#
#...#
.###.
@37 7
#####
....#
...#.
..#..
.#...
.#...
.#...
@38 8
.###.
#...#
#...#
.###.
#...#
#...#
.###.
@39 9
.###.
#...#
#...#
.####
....#
...#.
.##..
@3A :
..
##
##
..
##
##
..
@3B ;
..
##
##
..
##
.#
#.
@3C <
...#
..#.
.#..
#...
.#..
..#.
...#
@3D =
.....
.....
#####
.....
#####
.....
.....
@3E >
#...
.#..
..#.
...#
..#.
.#..
#...
@3F ?
.###.
#...#
....#
...#.
..#..
.....
..#..
@40 @
.###.
#...#
....#
.##.#
#.#.#
#.#.#
.###.
@41 A
.###.
#...#
#...#
#####
#...#
#...#
#...#
@42 B
####.
#...#
#...#
####.
#...#
#...#
####.
@43 C
.###.
#...#
#....
#....
#....
#...#
.###.
@44 D
###..
#..#.
#...#
#...#
#...#
#..#.
###..
@45 E
#####
#....
#....
####.
#....
#....
#####
@46 F
#####
#....
#....
####.
#....
#....
#....
@47 G
.###.
#...#
#....
#.###
#...#
#...#
.####
@48 H
#...#
#...#
#...#
#####
#...#
#...#
#...#
@49 I
###
.#.
.#.
.#.
.#.
.#.
###
@4A J
..###
...#.
...#.
...#.
...#.
#..#.
.##..
@4B K
#...#
#..#.
#.#..
##...
#.#..
#..#.
#...#
@4C L
#...
#...
#...
#...
#...
#...
####
@4D M
#...#
##.##
#.#.#
#.#.#
#...#
#...#
#...#
@4E N
#...#
#...#
##..#
#.#.#
#..##
#...#
#...#
@4F O
.###.
#...#
#...#
#...#
#...#
#...#
.###.
@50 P
####.
#...#
#...#
####.
#....
#....
#....
@51 Q
.###.
#...#
#...#
#...#
#.#.#
#..#.
.##.#
@52 R
####.
#...#
#...#
####.
#.#..
#..#.
#...#
@53 S
.####
#....
#....
.###.
....#
....#
####.
@54 T
#####
..#..
..#..
..#..
..#..
..#..
..#..
@55 U
#...#
#...#
#...#
#...#
#...#
#...#
.###.
@56 V
#...#
#...#
#...#
#...#
#...#
.#.#.
..#..
@57 W
#...#
#...#
#...#
#.#.#
#.#.#
#.#.#
.#.#.
@58 X
#...#
#...#
.#.#.
..#..
.#.#.
#...#
#...#
@59 Y
#...#
#...#
.#.#.
..#..
..#..
..#..
..#..
@5A Z
#####
....#
...#.
..#..
.#...
#....
#####
@5B [
###
#..
#..
#..
#..
#..
###
@5C \
.....
#....
.#...
..#..
...#.
....#
.....
@5D ]
###
..#
..#
..#
..#
..#
###
@5E ^
..#..
.#.#.
#...#
.....
.....
.....
.....
@5F _
.....
.....
.....
.....
.....
.....
.....
#####
@60 `
#.
.#
..
..
..
..
..
@61 a
.....
.....
.###.
....#
.####
#...#
.####
@62 b
#....
#....
#.##.
##..#
#...#
#...#
####.
@63 c
....
....
.###
#...
#...
#...
.###
@64 d
....#
....#
.##.#
#..##
#...#
#...#
.####
@65 e
.....
.....
.###.
#...#
#####
#....
.###.
@66 f
..##
.#..
.#..
###.
.#..
.#..
.#..
@67 g
.....
.....
.####
#...#
#...#
#...#
.####
....#
.###.
@68 h
#....
#....
#.##.
##..#
#...#
#...#
#...#
@69 i
#
.
#
#
#
#
#
@6A j
..#
...
..#
..#
..#
..#
..#
#.#
.#.
@6B k
#...
#...
#..#
#.#.
##..
#.#.
#..#
@6C l
##.
.#.
.#.
.#.
.#.
.#.
###
@6D m
.....
.....
##.#.
#.#.#
#.#.#
#.#.#
#.#.#
@6E n
.....
.....
#.##.
##..#
#...#
#...#
#...#
@6F o
.....
.....
.###.
#...#
#...#
#...#
.###.
@70 p
.....
.....
####.
#...#
#...#
#...#
####.
#....
#....
@71 q
.....
.....
.####
#...#
#...#
#...#
.####
....#
....#
@72 r
....
....
#.##
##..
#...
#...
#...
@73 s
.....
.....
.####
#....
.###.
....#
####.
@74 t
.#..
.#..
###.
.#..
.#..
.#.#
..#.
@75 u
.....
.....
#...#
#...#
#...#
#..##
.##.#
@76 v
.....
.....
#...#
#...#
#...#
.#.#.
..#..
@77 w
.....
.....
#...#
#...#
#.#.#
#.#.#
.#.#.
@78 x
.....
.....
#...#
.#.#.
..#..
.#.#.
#...#
@79 y
.....
.....
#...#
#...#
#...#
#...#
.####
....#
.###.
@7A z
.....
.....
#####
...#.
..#..
.#...
#####
@7B {
..##
.#..
.#..
#...
.#..
.#..
..##
@7C |
#
#
#
#
#
#
#
@7D }
##..
..#.
..#.
...#
..#.
..#.
##..
@7E ~
.....
.....
.#...
#.#.#
...#.
.....
.....
)font";

constexpr int kGlyphCount = kFontLastChar - kFontFirstChar + 1;
using FontTable = std::array<Glyph, kGlyphCount>;

// The pictures into row bits. Any defect in the pictures is a programming error: it
// throws std::logic_error naming the glyph, and the font unit test reaches it first.
FontTable parse_pictures() {
  FontTable table{};
  std::array<bool, kGlyphCount> seen{};
  int code = -1, rows = 0;
  auto close_glyph = [&] {
    if (code >= 0 && rows < 7)
      throw std::logic_error("font: glyph " + std::to_string(code) + " has " + std::to_string(rows) + " rows");
  };
  size_t pos = 0;
  while (pos < kFontPictures.size()) {
    size_t eol = kFontPictures.find('\n', pos);
    if (eol == std::string_view::npos) eol = kFontPictures.size();
    const std::string_view line = kFontPictures.substr(pos, eol - pos);
    pos = eol + 1;
    if (line.empty()) continue;
    if (line[0] == '@') {
      close_glyph();
      code = std::stoi(std::string(line.substr(1, 2)), nullptr, 16);
      if (code < kFontFirstChar || code > kFontLastChar || seen[size_t(code - kFontFirstChar)])
        throw std::logic_error("font: glyph header '" + std::string(line) + "' repeated or out of range");
      seen[size_t(code - kFontFirstChar)] = true;
      rows = 0;
      continue;
    }
    Glyph& g = table[size_t(code - kFontFirstChar)];
    if (code < 0 || rows == kFontRows || line.size() > size_t(kFontMaxWidth) ||
        (rows > 0 && int(line.size()) != g.width))
      throw std::logic_error("font: bad row '" + std::string(line) + "' in glyph " + std::to_string(code));
    g.width = int(line.size());
    uint8_t bits = 0;
    for (size_t c = 0; c < line.size(); ++c) {
      if (line[c] != '#' && line[c] != '.')
        throw std::logic_error("font: bad pixel in glyph " + std::to_string(code));
      if (line[c] == '#') bits = uint8_t(bits | 0x80u >> c);
    }
    g.rows[size_t(rows++)] = bits;
  }
  close_glyph();
  for (int i = 0; i < kGlyphCount; ++i)
    if (!seen[size_t(i)]) throw std::logic_error("font: no glyph for code " + std::to_string(i + kFontFirstChar));
  return table;
}

}  // namespace

const Glyph& font_glyph(char c) {
  static const FontTable table = parse_pictures();
  const int code = static_cast<unsigned char>(c);
  if (code < kFontFirstChar || code > kFontLastChar) throw std::logic_error("font_glyph: not printable ASCII");
  return table[size_t(code - kFontFirstChar)];
}

}  // namespace rastsim
