// SPDX-License-Identifier: Apache-2.0
#include "aa/coverage_error.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "aa/exact_coverage.h"
#include "ref/framebuffer.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/sample_pattern.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"

namespace rastsim {

double CoverageErrorStats::mean() const { return edge_pixels ? error_sum / double(edge_pixels) : 0.0; }
double CoverageErrorStats::rms() const { return edge_pixels ? std::sqrt(error_sq_sum / double(edge_pixels)) : 0.0; }

namespace {

PixelRect bounding_union(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

void add_error(CoverageErrorStats& s, double err) {
  ++s.edge_pixels;
  s.error_sum += err;
  s.error_sq_sum += err * err;
  s.error_max = std::max(s.error_max, err);
}

// One triangle's set-ups, one a sample count.
struct TriangleSetups {
  std::vector<SetupTriangle> tri;
  std::vector<char> measured, traversed;
  std::vector<std::vector<uint32_t>> masks;  // per sample count, row-major over the region
};

}  // namespace

CoverageErrorResult measure_coverage_error(const Scene& scene, const RasterState& arch, const std::vector<int>& samples) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int s : samples) {
    if (!valid_sample_count(s))
      throw std::invalid_argument("coverage error: sample count " + std::to_string(s) + " is not 1, 2, 4, 8 or 16");
    if (s > 1 && arch.traversal == Traversal::Scanline)
      throw std::invalid_argument("coverage error: " + std::to_string(s) +
                                  " samples need an exact traversal (tiled, bbox or hierarchical), not scanline");
  }
  const size_t K = samples.size();
  CoverageErrorResult r;
  r.per_samples.resize(K);
  for (size_t i = 0; i < K; ++i) r.per_samples[i].samples = samples[i];

  RasterState st = arch;
  Framebuffer fb(st.fb_width, st.fb_height);  // state commands only (clears)
  const int F = st.coord_format.frac_bits;
  const TraversalParams tp = traversal_params(st);
  TraversalCounters counters;  // not reported
  TriangleSetups ts;
  ts.tri.resize(K);
  ts.measured.resize(K);
  ts.traversed.resize(K);
  ts.masks.resize(K);

  for (const Command& cmd : scene.commands) {
    if (apply_state_command(cmd, st, fb)) continue;
    if (std::holds_alternative<CmdDraw2d>(cmd.body)) continue;  // 2D drawing has no triangles
    const auto& prims = std::get<CmdPrimitives>(cmd.body);
    const size_t n = triangle_count(prims);
    for (size_t k = 0; k < n; ++k) {
      const std::array<SceneVertex, 3> v = assemble_triangle(prims, k);
      PixelRect region;
      int geo = -1;  // a measured set-up: the snapped vertices are the same for every count
      for (size_t i = 0; i < K; ++i) {
        st.samples = samples[i];
        const SetupOutcome o = setup_triangle(v, st, cmd.loc, ts.tri[i]);
        ts.traversed[i] = o == SetupOutcome::Accepted;
        ts.measured[i] = ts.traversed[i] || o == SetupOutcome::CulledOutsideClip;
        if (!ts.measured[i]) continue;
        ++r.per_samples[i].triangles;
        geo = int(i);
        region = bounding_union(region, pixels_under_triangle(ts.tri[i], F));
        if (ts.traversed[i]) region = bounding_union(region, ts.tri[i].bbox);
      }
      if (geo < 0) continue;
      region = region.intersect(st.clip_rect());
      if (region.empty()) continue;
      const int w = region.x1 - region.x0;
      for (size_t i = 0; i < K; ++i) {
        if (!ts.measured[i]) continue;
        ts.masks[i].assign(size_t(region.area()), 0u);
        if (!ts.traversed[i]) continue;
        traverse(ts.tri[i], tp, counters, [&](int px, int py, uint32_t m) {
          ts.masks[i][size_t(py - region.y0) * size_t(w) + size_t(px - region.x0)] = m;
        });
      }
      const SetupTriangle& g = ts.tri[size_t(geo)];
      for (int py = region.y0; py < region.y1; ++py) {
        for (int px = region.x0; px < region.x1; ++px) {
          const size_t idx = size_t(py - region.y0) * size_t(w) + size_t(px - region.x0);
          const SquareClass cls = classify_pixel_square(g, px, py, F);
          if (cls != SquareClass::Boundary) {
            const int f = cls == SquareClass::Inside ? 1 : 0;
            for (size_t i = 0; i < K; ++i) {
              if (!ts.measured[i]) continue;
              const int S = samples[i], c = std::popcount(ts.masks[i][idx]);
              if (c != f * S) add_error(r.per_samples[i], std::fabs(double(c) / S - f));
            }
            continue;
          }
          ++r.pixels_clipped;
          const mpq_class f = exact_pixel_coverage(g, px, py, F);
          const bool strict = f > 0 && f < 1;
          for (size_t i = 0; i < K; ++i) {
            if (!ts.measured[i]) continue;
            mpq_class model(std::popcount(ts.masks[i][idx]), samples[i]);
            model.canonicalize();  // GMP needs reduced operands
            if (!strict && model == f) continue;
            add_error(r.per_samples[i], mpq_class(abs(model - f)).get_d());
          }
        }
      }
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace rastsim
