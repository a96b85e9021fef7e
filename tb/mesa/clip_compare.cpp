// SPDX-License-Identifier: Apache-2.0
// Clip-space coverage and colour, reference model against llvmpipe and the exact
// geometry (see clip_compare.h).
#include "clip_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "clip_geometry.h"
#include "ref/pipeline.h"

namespace rastsim::mesa {
namespace {

uint32_t pack(uint8_t r, uint8_t g, uint8_t b) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t{255} << 24;
}
bool covered(uint32_t rgba) { return (rgba >> 24) != 0; }

// Largest per-channel difference of two packed colours, in 8-bit LSBs.
uint32_t channel_diff(uint32_t a, uint32_t b) {
  uint32_t m = 0;
  for (int s = 0; s < 24; s += 8) m = std::max<uint32_t>(m, uint32_t(std::abs(int(a >> s & 0xff) - int(b >> s & 0xff))));
  return m;
}

uint32_t rounded(const std::array<double, 3>& c) {
  const auto ch = [](double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 255.0))); };
  return pack(ch(c[0]), ch(c[1]), ch(c[2]));
}

// Pixels that can be inside or within an LSB of the polygon: its bounding box widened
// by a pixel, clipped to the framebuffer.
PixelRect candidate_pixels(const VisiblePolygon& poly, int w, int h) {
  if (poly.empty()) return {};
  const std::vector<ScreenPoint>& pts = poly.vertices();
  double x0 = pts[0].x, x1 = x0, y0 = pts[0].y, y1 = y0;
  for (const ScreenPoint& p : pts) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  const auto clampi = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
  return {clampi(std::floor(x0) - 1, w), clampi(std::floor(y0) - 1, h), clampi(std::ceil(x1) + 1, w),
          clampi(std::ceil(y1) + 1, h)};
}

// One triangle's pixels: coverage and colour of both renderers against each other and
// against the oracle (the exact polygon and colour of `tri`, the triangle llvmpipe drew).
struct TriCompare {
  const ClipTri& tri;
  size_t index;
  const ViewRect& vp;
  const VisiblePolygon& poly;
  double lsb;  // px
  bool with_reference;
  ClipStats& s;
  std::vector<ClipMismatch>& report;
  size_t max_report;
  bool cut;  // a vertex outside near, far or +-w: clipping may make RGB8-rounded vertices

  // `candidate`: within the polygon's bounding box widened by a pixel; elsewhere the
  // centre is outside and far from every edge.
  void pixel(int x, int y, uint32_t lp, uint32_t rs, bool candidate) {
    const double cx = x + 0.5, cy = y + 0.5;
    const bool lc = covered(lp), rc = with_reference && covered(rs);
    if (const std::optional<EdgeKind> k = candidate ? poly.near_edge(cx, cy, lsb) : std::nullopt) {
      s.near_edge += lc || rc;
      s.near_mismatches += with_reference && lc != rc;
      s.near_mismatches_by_edge[size_t(*k)] += with_reference && lc != rc;
      return;
    }
    const bool inside = candidate && poly.inside(cx, cy);
    s.llvmpipe_far_errors += lc != inside;
    s.reference_far_errors += with_reference && rc != inside;
    if (lc != inside) note("llvmpipe differs from the exact coverage", x, y, lp, rs, inside, {});
    if (with_reference && lc != rc) {
      ++s.far_mismatches;
      note("coverage differs", x, y, lp, rs, inside, {});
    }
    if (lc && inside) colour(x, y, lp, rs);
  }

  // Interior pixel covered by llvmpipe: its colour against the exact one; with the
  // reference too, against it where snapping does not move the exact colour by more than
  // half an LSB (elsewhere the two may round apart: counted as colour-sensitive).
  void colour(int x, int y, uint32_t lp, uint32_t rs) {
    const std::array<double, 3> ex = exact_colour(tri, vp, x + 0.5, y + 0.5);
    const uint32_t le = channel_diff(lp, rounded(ex));
    s.llvmpipe_exact_max = std::max(s.llvmpipe_exact_max, le);
    s.llvmpipe_exact_over_1 += le > 1;
    if (!with_reference || !covered(rs)) return;
    const std::array<double, 3> sn = poly.snapped_colour(x + 0.5, y + 0.5, lsb);
    double shift = 0;
    for (int ch = 0; ch < 3; ++ch) shift = std::max(shift, std::abs(sn[size_t(ch)] - ex[size_t(ch)]));
    const uint32_t rsn = std::isfinite(shift) ? channel_diff(rs, rounded(sn)) : 0;
    s.reference_snapped_max = std::max(s.reference_snapped_max, rsn);
    s.reference_snapped_over_1 += rsn > 1;
    const uint32_t rl = channel_diff(rs, lp);
    if (!(shift <= 0.5)) {  // NaN: a degenerate snapped triangle
      ++s.colour_sensitive;
      s.sensitive_max = std::max(s.sensitive_max, rl);
      return;
    }
    const uint32_t re = channel_diff(rs, rounded(ex));
    ++s.colour_pixels;
    s.reference_exact_max = std::max(s.reference_exact_max, re);
    s.reference_exact_over_1 += re > 1;
    s.colour_max = std::max(s.colour_max, rl);
    if (rl > 1) {
      ++s.colour_over_1;
      s.colour_over_1_cut += cut;
      if (cut) s.colour_cut_max = std::max(s.colour_cut_max, rl);
      if (!cut) note("colour differs by more than 1", x, y, lp, rs, true, ex);
    }
  }

  void note(const char* what, int x, int y, uint32_t lp, uint32_t rs, bool inside, const std::array<double, 3>& ex) {
    if (report.size() < max_report)
      report.push_back({what, index, x, y, poly.edge_distance(x + 0.5, y + 0.5) / lsb, rs, lp, inside, ex});
  }
};

}  // namespace

ReferenceImage reference_image(const std::vector<ClipTri>& tris, const ViewRect& vp, const RasterState& st) {
  CmdPrimitives prims;  // a triangle list
  prims.topology = Topology::List;
  if (vp.x != 0 || vp.y != 0 || vp.width != st.viewport_width || vp.height != st.viewport_height)
    prims.clip.xform = ViewportXform{false, vp.x, vp.y, vp.width, vp.height};
  Scene scene;
  scene.source = "mesa-clip";
  ReferenceImage img;
  img.rgba.assign(size_t(st.fb_width) * size_t(st.fb_height), 0);
  for (const ClipTri& t : tris) prims.clip_vertices.insert(prims.clip_vertices.end(), t.v.begin(), t.v.end());
  scene.commands.push_back({std::move(prims), {"mesa-clip", 1}});
  // A fragment on a pixel already written: another triangle's (drawn later, it wins) or
  // the same one's (a repeat), told apart only for a single triangle.
  std::vector<uint8_t> seen(img.rgba.size(), 0);
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) {
    const size_t p = size_t(f.y) * size_t(st.fb_width) + size_t(f.x);
    img.repeats += tris.size() == 1 && seen[p];
    seen[p] = 1;
    img.rgba[p] = pack(f.r, f.g, f.b);
  });
  return img;
}

bool reference_draws_clip_space(const RasterState& st) {
  ClipTri t;  // half the viewport, all vertices inside the volume
  t.v[0] = {-1, -1, 0.5f, 1}, t.v[1] = {1, -1, 0.5f, 1}, t.v[2] = {-1, 1, 0.5f, 1};
  const ReferenceImage img = reference_image({t}, {0, 0, st.viewport_width, st.viewport_height}, st);
  return std::any_of(img.rgba.begin(), img.rgba.end(), covered);
}

ClipStats& ClipStats::operator+=(const ClipStats& o) {
  triangles += o.triangles, visible += o.visible;
  covered_reference += o.covered_reference, covered_llvmpipe += o.covered_llvmpipe;
  near_edge += o.near_edge, near_mismatches += o.near_mismatches, far_mismatches += o.far_mismatches;
  for (int k = 0; k < kEdgeKinds; ++k) near_mismatches_by_edge[size_t(k)] += o.near_mismatches_by_edge[size_t(k)];
  llvmpipe_far_errors += o.llvmpipe_far_errors, reference_far_errors += o.reference_far_errors;
  colour_pixels += o.colour_pixels, colour_over_1 += o.colour_over_1, colour_over_1_cut += o.colour_over_1_cut,
  colour_sensitive += o.colour_sensitive;
  colour_max = std::max(colour_max, o.colour_max);
  colour_cut_max = std::max(colour_cut_max, o.colour_cut_max);
  sensitive_max = std::max(sensitive_max, o.sensitive_max);
  reference_snapped_max = std::max(reference_snapped_max, o.reference_snapped_max);
  reference_snapped_over_1 += o.reference_snapped_over_1;
  llvmpipe_exact_max = std::max(llvmpipe_exact_max, o.llvmpipe_exact_max);
  reference_exact_max = std::max(reference_exact_max, o.reference_exact_max);
  llvmpipe_exact_over_1 += o.llvmpipe_exact_over_1, reference_exact_over_1 += o.reference_exact_over_1;
  repeats += o.repeats;
  return *this;
}

ClipStats compare_clip(const std::vector<ClipTri>& tris, const ViewRect& vp, const RasterState& st,
                       OsMesaClipRenderer& gl, bool with_reference, std::vector<ClipMismatch>& report,
                       size_t max_report, const std::vector<ClipTri>* reference_tris) {
  if (reference_tris && reference_tris->size() != tris.size()) throw std::invalid_argument("reference_tris size");
  ClipStats s;
  const int w = st.fb_width, h = st.fb_height;
  const double lsb = std::ldexp(1.0, -st.coord_format.frac_bits);
  const std::vector<uint32_t> none(size_t(w) * size_t(h), 0);
  for (size_t i = 0; i < tris.size(); ++i) {
    const VisiblePolygon poly(tris[i], vp);
    const std::vector<uint32_t> lp = gl.render({tris[i]}, vp);
    ReferenceImage ref;
    if (with_reference) ref = reference_image({(reference_tris ? *reference_tris : tris)[i]}, vp, st);
    const std::vector<uint32_t>& rs = with_reference ? ref.rgba : none;
    ++s.triangles;
    s.visible += !poly.empty();
    s.repeats += ref.repeats;
    const PixelRect box = candidate_pixels(poly, w, h);
    const bool cut = std::any_of(tris[i].v.begin(), tris[i].v.end(), [](const ClipVertex& c) {
      return c.z < 0 || c.z > c.w || c.x < -c.w || c.x > c.w || c.y < -c.w || c.y > c.w;
    });
    TriCompare tc{tris[i], i, vp, poly, lsb, with_reference, s, report, max_report, cut};
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = size_t(y) * size_t(w) + size_t(x);
        s.covered_llvmpipe += covered(lp[p]);
        s.covered_reference += covered(rs[p]);
        const bool candidate = x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1;
        if (candidate || covered(lp[p]) || covered(rs[p])) tc.pixel(x, y, lp[p], rs[p], candidate);
      }
  }
  return s;
}

std::string describe(const ClipMismatch& m, const std::vector<ClipTri>& tris, const ViewRect& vp) {
  const auto rgb = [](uint32_t c) {
    if (!covered(c)) return std::string("not covered");
    char b[32];
    std::snprintf(b, sizeof b, "(%u, %u, %u)", c & 0xff, c >> 8 & 0xff, c >> 16 & 0xff);
    return std::string(b);
  };
  char head[160];
  std::snprintf(head, sizeof head, "%s: triangle #%zu: pixel (%d, %d), %.2f LSB from an edge, exactly %s", m.what,
                m.tri, m.x, m.y, m.edge_lsb, m.exact_inside ? "inside" : "outside");
  std::string s = std::string(head) + ": rastsim " + rgb(m.reference) + ", llvmpipe " + rgb(m.llvmpipe);
  if (m.exact_inside) {
    char e[80];
    std::snprintf(e, sizeof e, ", exact colour (%.2f, %.2f, %.2f)", m.exact[0], m.exact[1], m.exact[2]);
    s += e;
  }
  return s + "\n" + describe(tris[m.tri], vp);
}

}  // namespace rastsim::mesa
