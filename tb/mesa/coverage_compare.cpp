// SPDX-License-Identifier: Apache-2.0
// Per-(triangle, pixel) coverage comparison, reference model against llvmpipe.
#include "coverage_compare.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "mesa_scenes.h"
#include "ref/pipeline.h"

namespace rastsim::mesa {

std::array<SceneVertex, 3> scene_vertices(const GridTri& t, size_t index) {
  std::array<SceneVertex, 3> out;
  for (int v = 0; v < 3; ++v) {
    SceneVertex& sv = out[size_t(v)];
    // Raw 2^-F px -> Q64 (64 fraction bits): an exact shift; only setup rounds (F > 8).
    sv.x = Q64{i128(t.x[v]) << (Q64::kFracBits - t.frac_bits)};
    sv.y = Q64{i128(t.y[v]) << (Q64::kFracBits - t.frac_bits)};
    sv.z = 0.5;
    // Constant colour = index + 1 (0 is the clear colour): interpolating a constant
    // gives it back exactly, so each fragment names its triangle.
    sv.r = uint8_t(index + 1), sv.g = 0, sv.b = 0;
  }
  return out;
}

Scene indexed_scene(const std::vector<GridTri>& tris) {
  if (tris.size() > size_t(kMaxTrisPerPass)) throw std::invalid_argument("more than 32 triangles in one pass");
  Scene scene;
  scene.source = "mesa";
  CmdPrimitives prims;  // a triangle list
  for (size_t i = 0; i < tris.size(); ++i)
    for (const SceneVertex& sv : scene_vertices(tris[i], i)) prims.vertices.push_back(sv);
  scene.commands.push_back({std::move(prims), {"mesa", 1}});
  return scene;
}

std::vector<uint32_t> reference_masks(const std::vector<GridTri>& tris, const RasterState& st) {
  const Scene scene = indexed_scene(tris);
  std::vector<uint32_t> masks(size_t(st.fb_width) * size_t(st.fb_height), 0);
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) {
    if (f.g != 0 || f.b != 0 || f.r == 0 || f.r > tris.size())
      throw std::logic_error("fragment colour is not a triangle index");
    const uint32_t bit = uint32_t{1} << (f.r - 1);
    uint32_t& m = masks[size_t(f.y) * st.fb_width + f.x];
    if (m & bit) throw std::logic_error("reference emitted a pixel twice for one triangle");
    m |= bit;
  });
  return masks;
}

uint64_t tie_pixels(const GridTri& t, int width, int height) {
  // Centre of pixel p in raw units: (2p + 1) * 2^(F-1). Coordinates < 2^24 raw, so every
  // edge product below is < 2^49: int64 is exact.
  const int f = t.frac_bits;
  const int64_t area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
  if (area2 == 0) return 0;  // degenerate: neither rasterizer draws it
  const int64_t sgn = area2 > 0 ? 1 : -1;
  const auto lo = [&](int64_t a, int64_t b, int64_t c, int n) {
    return int(std::clamp<int64_t>((std::min({a, b, c}) >> f) - 1, 0, n));
  };
  const auto hi = [&](int64_t a, int64_t b, int64_t c, int n) {
    return int(std::clamp<int64_t>((std::max({a, b, c}) >> f) + 2, 0, n));
  };
  const int x0 = lo(t.x[0], t.x[1], t.x[2], width), x1 = hi(t.x[0], t.x[1], t.x[2], width);
  const int y0 = lo(t.y[0], t.y[1], t.y[2], height), y1 = hi(t.y[0], t.y[1], t.y[2], height);
  uint64_t ties = 0;
  for (int py = y0; py < y1; ++py) {
    const int64_t sy = (2 * int64_t(py) + 1) << (f - 1);
    for (int px = x0; px < x1; ++px) {
      const int64_t sx = (2 * int64_t(px) + 1) << (f - 1);
      bool inside = true, on_edge = false;
      for (int i = 0; i < 3 && inside; ++i) {
        const int j = (i + 1) % 3;
        const int64_t e = sgn * ((t.x[j] - t.x[i]) * (sy - t.y[i]) - (t.y[j] - t.y[i]) * (sx - t.x[i]));
        inside = e >= 0;
        on_edge |= e == 0;
      }
      ties += inside && on_edge;
    }
  }
  return ties;
}

CompareStats& CompareStats::operator+=(const CompareStats& o) {
  triangles += o.triangles;
  passes += o.passes;
  decisions += o.decisions;
  covered += o.covered;
  mismatches += o.mismatches;
  ties += o.ties;
  return *this;
}

CompareStats compare_coverage(const std::vector<GridTri>& tris, const RasterState& st, OsMesaRenderer& gl,
                              std::vector<Mismatch>& report, size_t max_report) {
  CompareStats s;
  const int w = st.fb_width, h = st.fb_height;
  for (size_t first = 0; first < tris.size(); first += kMaxTrisPerPass) {
    const std::vector<GridTri> batch(tris.begin() + first,
                                     tris.begin() + std::min(tris.size(), first + kMaxTrisPerPass));
    const std::vector<uint32_t> ref = reference_masks(batch, st);
    const std::vector<uint32_t> lp = gl.coverage_masks(batch);
    ++s.passes;
    s.triangles += batch.size();
    s.decisions += uint64_t(batch.size()) * uint64_t(w) * uint64_t(h);
    for (const GridTri& t : batch) s.ties += tie_pixels(t, w, h);
    for (size_t p = 0; p < ref.size(); ++p) {
      s.covered += uint64_t(std::popcount(ref[p]));
      for (uint32_t diff = ref[p] ^ lp[p]; diff; diff &= diff - 1) {
        const int bit = std::countr_zero(diff);
        ++s.mismatches;
        if (report.size() < max_report)
          report.push_back({first + size_t(bit), int(p % size_t(w)), int(p / size_t(w)), bool(ref[p] >> bit & 1),
                            bool(lp[p] >> bit & 1)});
      }
    }
  }
  return s;
}

std::string describe(const Mismatch& m, const std::vector<GridTri>& tris) {
  return "triangle #" + std::to_string(m.tri) + " " + describe(tris[m.tri]) + ": pixel (" + std::to_string(m.x) +
         ", " + std::to_string(m.y) + "): rastsim " + (m.reference ? "covers" : "does not cover") + ", llvmpipe " +
         (m.llvmpipe ? "covers" : "does not cover");
}

}  // namespace rastsim::mesa
