// SPDX-License-Identifier: Apache-2.0
#include "ref/2d/draw2d.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "ref/2d/circle_raster.h"
#include "ref/2d/line_raster.h"
#include "ref/2d/point_raster.h"
#include "ref/2d/polygon_fill.h"
#include "ref/2d/raster2d.h"
#include "ref/2d/text_raster.h"

namespace rastsim {

namespace {

struct Snapped {
  int64_t x, y;  // absolute raw coordinates (F fraction bits)
};

// The front end of one command: appends its operations to `work`.
class FrontEnd {
 public:
  FrontEnd(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Draw2dWork& work)
      : cmd_(cmd), loc_(loc), st_(st), work_(work), F_(st.coord_format.frac_bits) {}

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
    switch (l.topology) {
      case LineTopology::Single:
      case LineTopology::List:
        for (size_t k = 0; k + 1 < n; k += 2) line((*v)[k], (*v)[k + 1]);
        break;
      case LineTopology::Strip:
      case LineTopology::Loop:
        for (size_t k = 0; k + 1 < n; ++k) line((*v)[k], (*v)[k + 1]);
        if (l.topology == LineTopology::Loop) line((*v)[n - 1], (*v)[0]);
        break;
    }
  }

  void operator()(const Draw2dCircle& c) {
    if (c.fill) {
      for (const PixelSpan& s : circle_fill(c.cx, c.cy, c.r)) span(s.y, s.x0, s.x1);
    } else {
      for (const auto& [x, y] : circle_outline(c.cx, c.cy, c.r)) pixel(x, y);
    }
  }

  void operator()(const Draw2dArc& a) {
    for (const auto& [x, y] : arc_outline(a.cx, a.cy, a.r, a.a0, a.a1)) pixel(x, y);
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

  // One rectangle fill per character cell, handed over as its runs: ink takes the
  // pattern, paper (opaque fonts only) the background colour.
  void operator()(const Draw2dText& t) {
    text_runs(t.x, t.y, t.str, t.style, [&](int y, int64_t x0, int64_t x1, bool ink) {
      constexpr int64_t kFar = int64_t(1) << 30;  // beyond any framebuffer, inside int
      span(y, int(std::clamp(x0, -kFar, kFar)), int(std::clamp(x1, -kFar, kFar)),
           ink ? Op2d::Paint::Pattern : Op2d::Paint::Background);
    });
  }

  void operator()(const Draw2dBlit& b) {
    const BlitRect r = clip_blit(st_.fb_width, st_.fb_height, work_.clip, b.sx, b.sy, b.dx, b.dy, b.w, b.h);
    if (r.empty()) return;
    Op2d op;
    op.kind = Op2d::Kind::Blit;
    op.sx = r.sx;
    op.sy = r.sy;
    op.x0 = r.dx;
    op.y0 = r.dy;
    op.w = r.w;
    op.h = r.h;
    work_.ops.push_back(op);
  }

 private:
  // Snaps every vertex; nullopt (culled) when one is outside the format in cull mode.
  std::optional<std::vector<Snapped>> snap(const std::vector<Vertex2d>& vs) {
    std::vector<Snapped> out;
    const int64_t ox = st_.origin_x(), oy = st_.origin_y(), one = st_.coord_format.one();
    for (size_t i = 0; i < vs.size(); ++i) {
      const auto x = snap_coord(vs[i].x, ox, st_.coord_format), y = snap_coord(vs[i].y, oy, st_.coord_format);
      if (!x || !y) {
        if (st_.out_of_range == OutOfRange::Cull) {
          work_.culled = true;
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

  // Index-method lines go to the line unit whole; diamond and DDA lines (no line unit
  // for them) reach the engine as their pixels in drawing order.
  void line(const Snapped& a, const Snapped& b) {
    auto px = [&](int x, int y) { pixel(x, y); };
    if (st_.line_method == LineMethod::Diamond) return diamond_line(a.x, a.y, b.x, b.y, F_, px);
    const int x0 = int(a.x >> F_), y0 = int(a.y >> F_), x1 = int(b.x >> F_), y1 = int(b.y >> F_);
    switch (st_.line_method) {
      case LineMethod::Bresenham:
      case LineMethod::Midpoint: {
        Op2d op;
        op.kind = Op2d::Kind::Line;
        op.midpoint = st_.line_method == LineMethod::Midpoint;
        op.x0 = x0;
        op.y0 = y0;
        op.x1 = x1;
        op.y1 = y1;
        work_.ops.push_back(op);
        break;
      }
      case LineMethod::Dda: dda_line(x0, y0, x1, y1, st_.dda_arith, F_, px); break;
      case LineMethod::Diamond: break;
    }
  }

  void pixel(int x, int y) {
    Op2d op;
    op.kind = Op2d::Kind::Pixel;
    op.x0 = x;
    op.y0 = y;
    work_.ops.push_back(op);
  }

  // A span clipped here; nothing when it is empty after clipping.
  void span(int y, int x0, int x1, Op2d::Paint paint = Op2d::Paint::Pattern) {
    const PixelRect r = PixelRect{x0, y, x1, y + 1}.intersect(work_.clip);
    if (r.empty()) return;
    Op2d op;
    op.kind = Op2d::Kind::Span;
    op.paint = paint;
    op.x0 = r.x0;
    op.x1 = r.x1;
    op.y0 = y;
    work_.ops.push_back(op);
  }

  const CmdDraw2d& cmd_;
  const SourceLoc& loc_;
  const RasterState& st_;
  Draw2dWork& work_;
  const int F_;
};

bool inside(const PixelRect& r, int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; }

}  // namespace

Draw2dWork draw2d_ops(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st) {
  Draw2dWork work;
  work.paint.fg = cmd.style.color;
  work.paint.bg = cmd.style.bgcolor;
  work.paint.pattern.rows = cmd.style.pattern;
  work.paint.pattern.solid = cmd.style.pattern_solid;
  work.paint.rop3 = cmd.style.rop3;
  work.clip = st.clip_rect().intersect({0, 0, st.fb_width, st.fb_height});
  std::visit(FrontEnd(cmd, loc, st, work), cmd.shape);
  if (work.culled) work.ops.clear();
  return work;
}

uint64_t draw2d_vertex_count(const CmdDraw2d& cmd) {
  constexpr uint64_t kInHeader = 0;  // a shape whose integers travel in the command header
  return std::visit(Overloaded{
      [](const Draw2dPoint&) { return uint64_t{1}; },
      [](const Draw2dLines& l) { return uint64_t(l.vertices.size()); },
      [](const Draw2dCircle&) { return kInHeader; },
      [](const Draw2dRect&) { return kInHeader; },
      [](const Draw2dPolygon& p) { return uint64_t(p.vertices.size()); },
      [](const Draw2dBlit&) { return kInHeader; },
      [](const Draw2dArc&) { return kInHeader; },
      // A string's bytes travel 8 to a vertex-sized word (two 32-bit coordinates).
      [](const Draw2dText& t) { return uint64_t((t.str.size() + 7) / 8); },
  }, cmd.shape);
}

uint64_t execute_op2d(Framebuffer& fb, const Draw2dWork& work, const Op2d& op, SurfaceClient* mem) {
  uint64_t written = 0;
  auto px = [&](int x, int y) {
    if (inside(work.clip, x, y)) written += fill_span(fb, work.clip, work.paint, y, x, x + 1, mem);
  };
  switch (op.kind) {
    case Op2d::Kind::Span: {
      if (op.paint == Op2d::Paint::Pattern) return fill_span(fb, work.clip, work.paint, op.y0, op.x0, op.x1, mem);
      Raster2dState solid = work.paint;
      solid.pattern.solid = true;
      if (op.paint == Op2d::Paint::Background) solid.fg = work.paint.bg;
      return fill_span(fb, work.clip, solid, op.y0, op.x0, op.x1, mem);
    }
    case Op2d::Kind::Pixel: px(op.x0, op.y0); break;
    case Op2d::Kind::Line:
      if (op.midpoint) midpoint_line(op.x0, op.y0, op.x1, op.y1, px);
      else bresenham_line(op.x0, op.y0, op.x1, op.y1, px);
      break;
    case Op2d::Kind::Blit: return blit_clipped(fb, work.paint, {op.sx, op.sy, op.x0, op.y0, op.w, op.h}, mem);
  }
  return written;
}

void draw_2d(const CmdDraw2d& cmd, const SourceLoc& loc, const RasterState& st, Framebuffer& fb, Draw2dStats& stats,
             SurfaceClient* mem) {
  const Draw2dWork work = draw2d_ops(cmd, loc, st);
  if (work.culled) {
    ++stats.primitives_culled;
    return;
  }
  ++stats.primitives;
  for (const Op2d& op : work.ops) stats.pixels += execute_op2d(fb, work, op, mem);
}

}  // namespace rastsim
