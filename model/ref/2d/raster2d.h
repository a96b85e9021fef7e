// SPDX-License-Identifier: Apache-2.0
// The 2D engine's pixel operations on the framebuffer (docs/2d-shapes.md): span fills
// with an 8x8 pattern through ROP3, and bit-block transfer.
//
// - Pattern: 8 rows of 8 bits, row 0 first, bit 7 = leftmost pixel; anchored to the
//   screen: pixel (x, y) uses row y mod 8, column x mod 8 (mod taken towards -inf). A 1
//   bit takes the foreground colour, a 0 bit the background colour. A solid pattern is
//   the foreground everywhere.
// - Every written pixel goes through ROP3 per colour channel (ref/2d/rop3.h) with P the
//   pattern colour at that pixel, S the source pixel (blit only) and D the destination;
//   alpha is written 255.
// - Clipping: fills are clipped to `clip` (the framebuffer, viewport and scissor);
//   a blit's source is clipped to the framebuffer and its destination to `clip`, both
//   in step so every written pixel keeps its source pixel.
// - A blit behaves as if the whole source rectangle were read before any write, so
//   overlapping copies in any direction give the source as it was. The hardware gets
//   there by its walk order (blit_walk_order): rows bottom to top when the copy moves
//   down, top to bottom otherwise; within a row right to left when the copy moves right
//   along the same rows, left to right otherwise. Every source pixel is read before the
//   walk overwrites it, and each destination pixel is written once.
// - Memory (`mem`, the colour surface's client rop_color when the memory system is on;
//   docs/memory.md, "The 2D engine"): each pixel makes, in order, a source read (a blit
//   whose code reads S), a destination read (a code that reads D) and the destination
//   write, each one access of the pixel's sample 0 (2D draws with one sample).
#pragma once

#include <array>
#include <cstdint>

#include "ref/framebuffer.h"
#include "ref/raster_state.h"

namespace rastsim {

class SurfaceClient;

struct Pattern8x8 {
  std::array<uint8_t, 8> rows{};  // row 0 first, bit 7 = leftmost pixel
  bool solid = true;              // `pattern solid`: the foreground everywhere
  bool bit(int x, int y) const { return solid || ((rows[size_t(y & 7)] >> (7 - (x & 7))) & 1); }
};

struct Raster2dState {
  std::array<uint8_t, 3> fg{}, bg{};  // current colour and background colour, R G B
  Pattern8x8 pattern;
  uint8_t rop3 = 0;                   // the ROP3 code (set by the trace; PATCOPY = 0xF0)
};

// A blit after clipping: w x h pixels from source (sx, sy) to destination (dx, dy).
struct BlitRect {
  int sx = 0, sy = 0, dx = 0, dy = 0, w = 0, h = 0;
  bool empty() const { return w <= 0 || h <= 0; }
};

// Clips a blit: the source to the fb_width x fb_height framebuffer, the destination to
// `clip` and the framebuffer, both in step so every destination pixel keeps its source.
BlitRect clip_blit(int fb_width, int fb_height, const PixelRect& clip, int sx, int sy, int dx, int dy, int w, int h);

// The overlap-safe walk of a clipped blit: rows bottom to top when `rows_up`, pixels
// right to left within a row when `right_to_left`.
struct BlitWalkOrder {
  bool rows_up = false, right_to_left = false;
};
inline BlitWalkOrder blit_walk_order(const BlitRect& b) { return {b.dy > b.sy, b.dy == b.sy && b.dx > b.sx}; }

// Copies a clipped blit pixel by pixel in the walk order. Returns pixels written.
uint64_t blit_clipped(Framebuffer& fb, const Raster2dState& st, const BlitRect& b, SurfaceClient* mem = nullptr);

// Fills pixels [x0, x1) of row y (clipped to `clip`) with the pattern through ROP3
// (no source operand: the caller rejects codes that read S). Returns pixels written.
uint64_t fill_span(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int y, int x0, int x1,
                   SurfaceClient* mem = nullptr);

// Copies the w x h rectangle at (sx, sy) to (dx, dy) through ROP3 (S = source pixel,
// D = destination, P = pattern at the destination). Returns pixels written.
uint64_t blit(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int sx, int sy, int dx, int dy, int w,
              int h);

}  // namespace rastsim
