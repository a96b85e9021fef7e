// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/raster2d.h"

#include <algorithm>
#include <utility>

#include "ref/2d/rop3.h"
#include "ref/memory/surface_client.h"

namespace rastsim {

namespace {

const std::array<uint8_t, 3>& pattern_color(const Raster2dState& st, int x, int y) {
  return st.pattern.bit(x, y) ? st.fg : st.bg;
}

// The pixel's accesses of the colour surface before its write (raster2d.h: a source
// read, a destination read, the write).
void count_accesses(SurfaceClient* mem, uint8_t code, int x, int y, const BlitRect* src_of = nullptr) {
  if (!mem) return;
  if (src_of && rop3_reads_source(code)) mem->access(x - src_of->dx + src_of->sx, y - src_of->dy + src_of->sy, 0, false);
  if (rop3_reads_destination(code)) mem->access(x, y, 0, false);
  mem->access(x, y, 0, true);
}

void write_pixel(uint8_t* d, const std::array<uint8_t, 3>& p, const uint8_t* s, uint8_t code) {
  for (int c = 0; c < 3; ++c) d[c] = rop3(code, p[size_t(c)], s ? s[c] : 0, d[c]);
  d[3] = 255;
}

}  // namespace

uint64_t fill_span(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int y, int x0, int x1,
                   SurfaceClient* mem) {
  const PixelRect r = PixelRect{x0, y, x1, y + 1}.intersect(clip).intersect({0, 0, fb.width, fb.height});
  if (r.empty()) return 0;
  for (int x = r.x0; x < r.x1; ++x) {
    count_accesses(mem, st.rop3, x, y);
    write_pixel(fb.pixel(x, y), pattern_color(st, x, y), nullptr, st.rop3);
  }
  return uint64_t(r.x1 - r.x0);
}

BlitRect clip_blit(int fb_width, int fb_height, const PixelRect& clip, int sx, int sy, int dx, int dy, int w, int h) {
  if (w <= 0 || h <= 0) return {};
  // Clip in destination space: the destination box, the clip box, and the source box
  // clipped to the framebuffer moved by the copy's offset. (64-bit offsets: no overflow.)
  const int64_t ox = int64_t(dx) - sx, oy = int64_t(dy) - sy;
  const PixelRect fb_rect{0, 0, fb_width, fb_height};
  const PixelRect src = PixelRect{sx, sy, sx + w, sy + h}.intersect(fb_rect);
  auto clamp = [](int64_t v) { return int(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX)); };
  const PixelRect src_in_dst{clamp(src.x0 + ox), clamp(src.y0 + oy), clamp(src.x1 + ox), clamp(src.y1 + oy)};
  const PixelRect r = PixelRect{dx, dy, dx + w, dy + h}.intersect(clip).intersect(fb_rect).intersect(src_in_dst);
  if (r.empty()) return {};
  return {int(r.x0 - ox), int(r.y0 - oy), r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0};
}

uint64_t blit_clipped(Framebuffer& fb, const Raster2dState& st, const BlitRect& b, SurfaceClient* mem) {
  if (b.empty()) return 0;
  const BlitWalkOrder o = blit_walk_order(b);
  for (int j = 0; j < b.h; ++j) {
    const int y = o.rows_up ? b.h - 1 - j : j;
    for (int i = 0; i < b.w; ++i) {
      const int x = o.right_to_left ? b.w - 1 - i : i;
      uint8_t s[4];
      std::copy_n(std::as_const(fb).pixel(b.sx + x, b.sy + y), 4, s);  // a read: no tile allocated
      count_accesses(mem, st.rop3, b.dx + x, b.dy + y, &b);
      write_pixel(fb.pixel(b.dx + x, b.dy + y), pattern_color(st, b.dx + x, b.dy + y), s, st.rop3);
    }
  }
  return uint64_t(b.w) * uint64_t(b.h);
}

uint64_t blit(Framebuffer& fb, const PixelRect& clip, const Raster2dState& st, int sx, int sy, int dx, int dy, int w,
              int h) {
  return blit_clipped(fb, st, clip_blit(fb.width, fb.height, clip, sx, sy, dx, dy, w, h));
}

}  // namespace rastsim
