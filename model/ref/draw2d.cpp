// SPDX-License-Identifier: Apache-2.0
#include "ref/draw2d.h"

#include <optional>
#include <vector>

#include "ref/circle_raster.h"
#include "ref/line_raster.h"
#include "ref/point_raster.h"
#include "ref/polygon_fill.h"
#include "ref/raster2d.h"

namespace rastsim {

namespace {

struct Snapped {
  int64_t x, y;  // absolute raw coordinates (F fraction bits)
};

class Drawer {
 public:
  Drawer(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Framebuffer& fb, Draw2dStats& stats)
      : cmd_(cmd), loc_(loc), st_(st), fb_(fb), stats_(stats), clip_(st.clip_rect()), F_(st.coord_format.frac_bits) {
    ops_.fg = cmd.style.color;
    ops_.bg = cmd.style.bgcolor;
    ops_.pattern.rows = cmd.style.pattern;
    ops_.pattern.solid = cmd.style.pattern_solid;
    ops_.rop3 = cmd.style.rop3;
  }

  void operator()(const Draw2dPoint& p) {
    const auto v = snap({p.p});
    if (!v) return;
    const PixelRect r = point_pixels((*v)[0].x, (*v)[0].y, cmd_.style.point_size, F_);
    for (int y = r.y0; y < r.y1; ++y) span(y, r.x0, r.x1);
  }

  void operator()(const Draw2dLines& l) {
    const auto v = snap(l.vertices);
    if (!v) return;
    const size_t n = v->size();
    auto seg = [&](const Snapped& a, const Snapped& b) { line(a, b); };
    switch (l.topology) {
      case LineTopology::Single:
      case LineTopology::List:
        for (size_t k = 0; k + 1 < n; k += 2) seg((*v)[k], (*v)[k + 1]);
        break;
      case LineTopology::Strip:
      case LineTopology::Loop:
        for (size_t k = 0; k + 1 < n; ++k) seg((*v)[k], (*v)[k + 1]);
        if (l.topology == LineTopology::Loop) seg((*v)[n - 1], (*v)[0]);
        break;
    }
  }

  void operator()(const Draw2dCircle& c) {
    if (c.fill) {
      for (const PixelSpan& s : circle_fill(c.cx, c.cy, c.r)) span(s.y, s.x0, s.x1);
    } else {
      for (const auto& [x, y] : circle_outline(c.cx, c.cy, c.r)) span(y, x, x + 1);
    }
  }

  void operator()(const Draw2dRect& r) {
    for (int64_t y = r.y; y < int64_t(r.y) + r.h; ++y) span(int(y), r.x, int(int64_t(r.x) + r.w));
  }

  void operator()(const Draw2dPolygon& p) {
    const auto v = snap(p.vertices);
    if (!v) return;
    std::vector<std::pair<int64_t, int64_t>> raw;
    for (const Snapped& s : *v) raw.emplace_back(s.x, s.y);
    for (const PixelSpan& s : fill_polygon(raw, F_, st_.polygon_rule)) span(s.y, s.x0, s.x1);
  }

  void operator()(const Draw2dBlit& b) { stats_.pixels += blit(fb_, clip_, ops_, b.sx, b.sy, b.dx, b.dy, b.w, b.h); }

 private:
  // Snaps every vertex; nullopt (counted) when one is outside the format in cull mode.
  std::optional<std::vector<Snapped>> snap(const std::vector<Vertex2d>& vs) {
    std::vector<Snapped> out;
    const int64_t ox = st_.origin_x(), oy = st_.origin_y(), one = st_.coord_format.one();
    for (size_t i = 0; i < vs.size(); ++i) {
      const auto x = snap_coord(vs[i].x, ox, st_.coord_format), y = snap_coord(vs[i].y, oy, st_.coord_format);
      if (!x || !y) {
        if (st_.out_of_range == OutOfRange::Cull) {
          ++stats_.primitives_culled;
          return std::nullopt;
        }
        throw SceneError(loc_.str() + ": '" + cmd_.keyword + "' vertex " + std::to_string(i) + " (" +
                         std::to_string(vs[i].x.to_double()) + ", " + std::to_string(vs[i].y.to_double()) +
                         ") is outside raster.coord_format " + st_.coord_format.name() +
                         " around the viewport centre (raster.out_of_range = cull drops it instead)");
      }
      out.push_back({*x + ox * one, *y + oy * one});
    }
    return out;
  }

  void line(const Snapped& a, const Snapped& b) {
    auto px = [&](int x, int y) { span(y, x, x + 1); };
    if (st_.line_method == LineMethod::Diamond) return diamond_line(a.x, a.y, b.x, b.y, F_, px);
    const int x0 = int(a.x >> F_), y0 = int(a.y >> F_), x1 = int(b.x >> F_), y1 = int(b.y >> F_);
    switch (st_.line_method) {
      case LineMethod::Bresenham: bresenham_line(x0, y0, x1, y1, px); break;
      case LineMethod::Midpoint: midpoint_line(x0, y0, x1, y1, px); break;
      case LineMethod::Dda: dda_line(x0, y0, x1, y1, st_.dda_arith, F_, px); break;
      case LineMethod::Diamond: break;
    }
  }

  void span(int y, int x0, int x1) { stats_.pixels += fill_span(fb_, clip_, ops_, y, x0, x1); }

  const CmdDraw2d& cmd_;
  const SourceLoc& loc_;
  const RasterState& st_;
  Framebuffer& fb_;
  Draw2dStats& stats_;
  const PixelRect clip_;
  const int F_;
  Raster2dState ops_;
};

}  // namespace

void draw_2d(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Framebuffer& fb, Draw2dStats& stats) {
  const uint64_t culled = stats.primitives_culled;
  std::visit(Drawer(cmd, loc, st, fb, stats), cmd.shape);
  if (stats.primitives_culled == culled) ++stats.primitives;
}

}  // namespace rastsim
