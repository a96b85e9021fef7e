// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/text_raster.h"

namespace rastsim {

TextCell text_cell(char c, const TextStyle& style) {
  TextCell cell;
  cell.glyph = &font_glyph(c);
  cell.bold = style.bold;
  cell.underline = style.underline;
  const int bold = style.bold ? 1 : 0;
  if (style.proportional) {
    cell.advance = cell.glyph->width + bold + 1;
  } else {
    cell.offset = (kFontMaxWidth - cell.glyph->width) / 2;
    cell.advance = kFontMaxWidth + bold + 1;
  }
  return cell;
}

int64_t text_width(std::string_view str, const TextStyle& style) {
  int64_t w = 0;
  for (char c : str) w += text_cell(c, style).advance;
  return w * style.scale;
}

}  // namespace rastsim
