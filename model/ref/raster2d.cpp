// SPDX-License-Identifier: Apache-2.0
#include "ref/raster2d.h"

#include <algorithm>
#include <vector>

#include "ref/rop3.h"

namespace rastsim {

namespace {

const std::array<uint8_t, 3>& pattern_color(const Raster2dState& st, int x, int y) {
  return st.pattern.bit(x, y) ? st.fg : st.bg;
}

void write_pixel(uint8_t* d, const std::array<uint8_t, 3>& p, const uint8_t* s, uint8_t code) {
  for (int c = 0; c < 3; ++c) d[c] = rop3(code, p[size_t(c)], s ? s[c] : 0, d[c]);
  d[3] = 255;
}

}  // namespace

uint64_t fill_span(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int y, int x0, int x1) {
  const PixelRect r = PixelRect{x0, y, x1, y + 1}.intersect(clip).intersect({0, 0, fb.width, fb.height});
  if (r.empty()) return 0;
  for (int x = r.x0; x < r.x1; ++x) write_pixel(fb.pixel(x, y), pattern_color(st, x, y), nullptr, st.rop3);
  return uint64_t(r.x1 - r.x0);
}

uint64_t blit(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int sx, int sy, int dx, int dy, int w,
              int h) {
  if (w <= 0 || h <= 0) return 0;
  // Clip in destination space: the destination box, the clip box, and the source box
  // clipped to the framebuffer moved by the copy's offset. (64-bit offsets: no overflow.)
  const int64_t ox = int64_t(dx) - sx, oy = int64_t(dy) - sy;
  const PixelRect fb_rect{0, 0, fb.width, fb.height};
  const PixelRect src = PixelRect{sx, sy, sx + w, sy + h}.intersect(fb_rect);
  const PixelRect src_in_dst{int(std::clamp<int64_t>(src.x0 + ox, INT32_MIN, INT32_MAX)),
                             int(std::clamp<int64_t>(src.y0 + oy, INT32_MIN, INT32_MAX)),
                             int(std::clamp<int64_t>(src.x1 + ox, INT32_MIN, INT32_MAX)),
                             int(std::clamp<int64_t>(src.y1 + oy, INT32_MIN, INT32_MAX))};
  const PixelRect r = PixelRect{dx, dy, dx + w, dy + h}.intersect(clip).intersect(fb_rect).intersect(src_in_dst);
  if (r.empty()) return 0;
  // Read the whole source first: overlapping copies see the source as it was.
  const int rw = r.x1 - r.x0, rh = r.y1 - r.y0;
  std::vector<uint8_t> source(size_t(rw) * rh * 4);
  for (int y = 0; y < rh; ++y)
    std::copy_n(fb.pixel(int(r.x0 - ox), int(r.y0 + y - oy)), size_t(rw) * 4, &source[size_t(y) * rw * 4]);
  for (int y = 0; y < rh; ++y)
    for (int x = 0; x < rw; ++x)
      write_pixel(fb.pixel(r.x0 + x, r.y0 + y), pattern_color(st, r.x0 + x, r.y0 + y),
                  &source[(size_t(y) * rw + x) * 4], st.rop3);
  return uint64_t(rw) * rh;
}

}  // namespace rastsim
