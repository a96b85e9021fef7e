// SPDX-License-Identifier: Apache-2.0
// Per-(triangle, pixel) 4x sample coverage, reference model against llvmpipe.
#include "msaa_compare.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "coverage_compare.h"
#include "mesa_scenes.h"
#include "ref/fine_raster.h"
#include "ref/pipeline.h"
#include "ref/tri_setup.h"

namespace rastsim::mesa {

SampleMasks reference_sample_masks(const std::vector<GridTri>& tris, const RasterState& st) {
  if (st.samples != kMsaaSamples) throw std::invalid_argument("reference_sample_masks needs raster.samples = 4");
  const Scene scene = indexed_scene(tris);
  SampleMasks masks;
  for (auto& m : masks) m.assign(size_t(st.fb_width) * size_t(st.fb_height), 0);
  std::vector<uint32_t> seen(masks[0].size(), 0);
  RenderStats stats;
  render_scene(scene, st, stats, [&](const Fragment& f) {
    if (f.g != 0 || f.b != 0 || f.r == 0 || f.r > tris.size())
      throw std::logic_error("fragment colour is not a triangle index");
    if (f.mask == 0 || f.mask >= (1u << kMsaaSamples)) throw std::logic_error("fragment sample mask out of range");
    const uint32_t bit = uint32_t{1} << (f.r - 1);
    const size_t p = size_t(f.y) * size_t(st.fb_width) + size_t(f.x);
    if (seen[p] & bit) throw std::logic_error("reference emitted a pixel twice for one triangle");
    seen[p] |= bit;
    for (int s = 0; s < kMsaaSamples; ++s)
      if (f.mask >> s & 1) masks[size_t(s)][p] |= bit;
  });
  return masks;
}

SampleMasks direct_sample_masks(const std::vector<GridTri>& tris, const RasterState& st, uint64_t* on_edge) {
  if (tris.size() > size_t(kMaxTrisPerPass)) throw std::invalid_argument("more than 32 triangles in one pass");
  const int w = st.fb_width, h = st.fb_height, f = st.coord_format.frac_bits;
  SampleMasks masks;
  for (auto& m : masks) m.assign(size_t(w) * size_t(h), 0);
  for (size_t i = 0; i < tris.size(); ++i) {
    SetupTriangle t;
    if (setup_triangle(scene_vertices(tris[i], i), st, {"mesa", 1}, t) != SetupOutcome::Accepted) continue;
    const SampleEdgeOffsets so(t, f);
    const int x0 = std::max(t.bbox.x0 - 1, 0), x1 = std::min(t.bbox.x1 + 1, w);
    const int y0 = std::max(t.bbox.y0 - 1, 0), y1 = std::min(t.bbox.y1 + 1, h);
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) {
        const uint32_t m = pixel_sample_mask(t, px, py, f);
        for (int s = 0; s < kMsaaSamples; ++s)
          if (m >> s & 1) masks[size_t(s)][size_t(py) * size_t(w) + size_t(px)] |= uint32_t{1} << i;
        if (!on_edge) continue;
        // Samples of the closed triangle (no bias) with an edge value of exactly 0.
        const int64_t sx = t.sample_x(px, f), sy = t.sample_y(py, f);
        for (int s = 0; s < kMsaaSamples; ++s) {
          bool inside = true, edge = false;
          for (int e = 0; e < 3; ++e) {
            const i128 v = t.edge[size_t(e)].eval(sx, sy) + so.off[size_t(e)][size_t(s)];
            inside = inside && v >= 0;
            edge = edge || v == 0;
          }
          *on_edge += inside && edge;
        }
      }
  }
  return masks;
}

MsaaStats& MsaaStats::operator+=(const MsaaStats& o) {
  triangles += o.triangles;
  passes += o.passes;
  decisions += o.decisions;
  sample_decisions += o.sample_decisions;
  pixels_covered += o.pixels_covered;
  pixels_partial += o.pixels_partial;
  samples_covered += o.samples_covered;
  samples_on_edge += o.samples_on_edge;
  count_mismatches += o.count_mismatches;
  mask_mismatches += o.mask_mismatches;
  pipeline_vs_direct += o.pipeline_vs_direct;
  return *this;
}

MsaaStats compare_msaa(const std::vector<GridTri>& tris, const RasterState& st, OsMesaMsaa& gl,
                       std::vector<MsaaMismatch>& report, size_t max_report) {
  MsaaStats s;
  const size_t w = size_t(st.fb_width), n = w * size_t(st.fb_height);
  for (size_t first = 0; first < tris.size(); first += kMaxTrisPerPass) {
    const std::vector<GridTri> batch(tris.begin() + first,
                                     tris.begin() + std::min(tris.size(), first + kMaxTrisPerPass));
    const SampleMasks pipe = reference_sample_masks(batch, st);
    const SampleMasks direct = direct_sample_masks(batch, st, &s.samples_on_edge);
    const SampleMasks lp = gl.sample_masks(batch);
    ++s.passes;
    s.triangles += batch.size();
    s.decisions += uint64_t(batch.size()) * n;
    s.sample_decisions += uint64_t(batch.size()) * n * kMsaaSamples;
    for (size_t p = 0; p < n; ++p) {
      uint32_t any_ref = 0, any_diff = 0, any_pipe_diff = 0;
      for (int k = 0; k < kMsaaSamples; ++k) {
        any_ref |= direct[size_t(k)][p];
        any_diff |= direct[size_t(k)][p] ^ lp[size_t(k)][p];
        any_pipe_diff |= direct[size_t(k)][p] ^ pipe[size_t(k)][p];
      }
      s.pipeline_vs_direct += uint64_t(std::popcount(any_pipe_diff));
      for (uint32_t bits = any_ref; bits; bits &= bits - 1) {
        const int c = std::popcount(tri_mask(direct, p, std::countr_zero(bits)));
        ++s.pixels_covered;
        s.pixels_partial += c < kMsaaSamples;
        s.samples_covered += uint64_t(c);
      }
      for (; any_diff; any_diff &= any_diff - 1) {
        const int bit = std::countr_zero(any_diff);
        const uint32_t ref = tri_mask(direct, p, bit), got = tri_mask(lp, p, bit);
        ++s.mask_mismatches;
        s.count_mismatches += std::popcount(ref) != std::popcount(got);
        if (report.size() < max_report)
          report.push_back({first + size_t(bit), int(p % w), int(p / w), ref, got});
      }
    }
  }
  return s;
}

std::string describe(const MsaaMismatch& m, const std::vector<GridTri>& tris) {
  const auto bits = [](uint32_t v) {
    std::string s;
    for (int k = 0; k < kMsaaSamples; ++k) s += char('0' + (v >> k & 1));
    return s + " (" + std::to_string(std::popcount(v)) + ")";
  };
  return "triangle #" + std::to_string(m.tri) + " " + describe(tris[m.tri]) + ": pixel (" + std::to_string(m.x) +
         ", " + std::to_string(m.y) + "): rastsim samples " + bits(m.reference) + ", llvmpipe " + bits(m.llvmpipe);
}

}  // namespace rastsim::mesa
