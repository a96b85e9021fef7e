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

void check_sample_counts(const RasterState& arch, const std::vector<int>& samples) {
  for (int s : samples) {
    if (!valid_sample_count(s))
      throw std::invalid_argument("coverage error: sample count " + std::to_string(s) + " is not 1, 2, 4, 8 or 16");
    if (s > 1 && arch.traversal == Traversal::Scanline)
      throw std::invalid_argument("coverage error: " + std::to_string(s) +
                                  " samples need an exact traversal (tiled, bbox or hierarchical), not scanline");
  }
}

// The study's walk of the scene: state commands applied in order, each triangle set up
// once a sample count (set_up), traversed (traverse_counts) and its region's pixels
// compared with the exact coverage (compare_region).
class CoverageMeasure {
 public:
  CoverageMeasure(const RasterState& arch, const std::vector<int>& samples, CoverageErrorResult& r)
      : samples_(samples), K_(samples.size()), st_(arch), fb_(st_.fb_width, st_.fb_height),
        F_(st_.coord_format.frac_bits), tp_(traversal_params(st_)), r_(r), tri_(K_), measured_(K_),
        traversed_(K_), masks_(K_) {
    r_.per_samples.resize(K_);
    for (size_t i = 0; i < K_; ++i) r_.per_samples[i].samples = samples[i];
  }

  void command(const Command& cmd) {
    const auto state = [&] { apply_state_command(cmd, st_, fb_); };
    visit_command(cmd, Overloaded{
        state_commands(state),
        [&](const CmdPrimitives& prims) {
          for_each_triangle(prims, st_, cmd.loc, front_end_, [&](const ScreenTriangle& v) { triangle(v, cmd.loc); });
        },
        [](const CmdDraw2d&) {},  // 2D drawing has no triangles
    });
  }

 private:
  void triangle(const std::array<SceneVertex, 3>& v, const SourceLoc& loc) {
    PixelRect region;
    const int geo = set_up(v, loc, region);
    if (geo < 0) return;
    region = region.intersect(st_.clip_rect());
    if (region.empty()) return;
    traverse_counts(region);
    compare_region(tri_[size_t(geo)], region);
  }

  // Sets the triangle up at every sample count; returns a measured count's index (its
  // snapped vertices are every count's), or -1 if none is measured, and the union of
  // the measured set-ups' pixels in `region`.
  int set_up(const std::array<SceneVertex, 3>& v, const SourceLoc& loc, PixelRect& region) {
    int geo = -1;
    for (size_t i = 0; i < K_; ++i) {
      st_.samples = samples_[i];
      const SetupOutcome o = setup_triangle(v, st_, loc, tri_[i]);
      traversed_[i] = o == SetupOutcome::Accepted;
      measured_[i] = traversed_[i] || o == SetupOutcome::CulledOutsideClip;
      if (!measured_[i]) continue;
      ++r_.per_samples[i].triangles;
      geo = int(i);
      region = bounding_union(region, pixels_under_triangle(tri_[i], F_));
      if (traversed_[i]) region = bounding_union(region, tri_[i].bbox);
    }
    return geo;
  }

  // Each measured count's masks over `region` (row-major), empty where not traversed.
  void traverse_counts(const PixelRect& region) {
    for (size_t i = 0; i < K_; ++i) {
      if (!measured_[i]) continue;
      masks_[i].assign(size_t(region.area()), 0u);
      if (!traversed_[i]) continue;
      traverse(tri_[i], tp_, counters_, [&](int px, int py, uint32_t m) { masks_[i][index(region, px, py)] = m; });
    }
  }

  void compare_region(const SetupTriangle& g, const PixelRect& region) {
    for (int py = region.y0; py < region.y1; ++py)
      for (int px = region.x0; px < region.x1; ++px) {
        const size_t idx = index(region, px, py);
        const SquareClass cls = classify_pixel_square(g, px, py, F_);
        if (cls == SquareClass::Boundary) compare_boundary_pixel(g, px, py, idx);
        else compare_whole_pixel(cls == SquareClass::Inside ? 1 : 0, idx);
      }
  }

  // A pixel square wholly inside (f = 1) or outside (f = 0) the triangle.
  void compare_whole_pixel(int f, size_t idx) {
    for (size_t i = 0; i < K_; ++i) {
      if (!measured_[i]) continue;
      const int S = samples_[i], c = std::popcount(masks_[i][idx]);
      if (c != f * S) add_error(r_.per_samples[i], std::fabs(double(c) / S - f));
    }
  }

  // A pixel square an edge crosses: its exact coverage by the rational clip.
  void compare_boundary_pixel(const SetupTriangle& g, int px, int py, size_t idx) {
    ++r_.pixels_clipped;
    const mpq_class f = exact_pixel_coverage(g, px, py, F_);
    const bool strict = f > 0 && f < 1;
    for (size_t i = 0; i < K_; ++i) {
      if (!measured_[i]) continue;
      mpq_class model(std::popcount(masks_[i][idx]), samples_[i]);
      model.canonicalize();  // GMP needs reduced operands
      if (!strict && model == f) continue;
      add_error(r_.per_samples[i], mpq_class(abs(model - f)).get_d());
    }
  }

  static size_t index(const PixelRect& region, int px, int py) {
    return size_t(py - region.y0) * size_t(region.x1 - region.x0) + size_t(px - region.x0);
  }

  const std::vector<int>& samples_;
  const size_t K_;
  RasterState st_;
  Framebuffer fb_;  // state commands only (clears)
  const int F_;
  const TraversalParams tp_;
  TraversalCounters counters_;  // not reported
  FrontEndStats front_end_;     // not reported
  CoverageErrorResult& r_;
  // One triangle's set-ups, one a sample count.
  std::vector<SetupTriangle> tri_;
  std::vector<char> measured_, traversed_;
  std::vector<std::vector<uint32_t>> masks_;  // per sample count, row-major over the region
};

}  // namespace

CoverageErrorResult measure_coverage_error(const Scene& scene, const RasterState& arch, const std::vector<int>& samples) {
  const auto t0 = std::chrono::steady_clock::now();
  check_sample_counts(arch, samples);
  CoverageErrorResult r;
  CoverageMeasure measure(arch, samples, r);
  for (const Command& cmd : scene.commands) measure.command(cmd);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace rastsim
