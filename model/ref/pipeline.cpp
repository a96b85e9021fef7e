// SPDX-License-Identifier: Apache-2.0
#include "ref/pipeline.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "ref/prim_assembly.h"
#include "ref/rop.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"

namespace rastsim {

bool count_setup_outcome(SetupOutcome o, RenderStats& stats) {
  switch (o) {
    case SetupOutcome::Accepted: ++stats.triangles_rasterized; return true;
    case SetupOutcome::CulledZeroArea:
      ++stats.triangles_culled;
      ++stats.triangles_zero_area;
      return false;
    case SetupOutcome::CulledBackFace:
    case SetupOutcome::CulledFrontFace:
      ++stats.triangles_culled;
      ++stats.triangles_facing_culled;
      return false;
    case SetupOutcome::CulledOutOfRange: ++stats.triangles_out_of_range; return false;
    case SetupOutcome::CulledOutsideClip: ++stats.triangles_outside_clip; return false;
  }
  return false;
}

bool apply_state_command(const Command& cmd, RasterState& st, Framebuffer& fb) {
  return std::visit(
      [&](const auto& c) -> bool {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, CmdViewport>) {
          const int64_t max_extent = max_viewport_extent(st.coord_format);
          if (c.width < 1 || c.height < 1 || c.width > st.fb_width || c.height > st.fb_height)
            throw SceneError(cmd.loc.str() + ": viewport " + std::to_string(c.width) + "x" +
                             std::to_string(c.height) + " does not fit the " + std::to_string(st.fb_width) +
                             "x" + std::to_string(st.fb_height) +
                             " framebuffer (display.width x display.height)");
          if (c.width > max_extent || c.height > max_extent)
            throw SceneError(cmd.loc.str() + ": viewport " + std::to_string(c.width) + "x" +
                             std::to_string(c.height) + " does not fit raster.coord_format " +
                             st.coord_format.name() + " (largest " + std::to_string(max_extent) + " px)");
          st.viewport_width = c.width;
          st.viewport_height = c.height;
          return true;
        } else if constexpr (std::is_same_v<C, CmdClear>) {
          fb.clear_color(c.r, c.g, c.b);
          return true;
        } else if constexpr (std::is_same_v<C, CmdClearDepth>) {
          const auto z = quantize_unorm(c.z, st.depth_bits);
          if (!z) throw SceneError(cmd.loc.str() + ": clear depth must be in [0, 1]");
          fb.clear_depth(*z);
          return true;
        } else if constexpr (std::is_same_v<C, CmdScissor>) {
          st.scissor_enabled = c.enabled;
          st.scissor = {c.x, c.y, c.x + c.width, c.y + c.height};
          return true;
        } else {
          return false;
        }
      },
      cmd.body);
}

void count_multisample_footprint(const RasterState& st, RenderStats& stats) {
  const uint64_t pixels = uint64_t(st.fb_width) * uint64_t(st.fb_height), S = uint64_t(st.samples);
  stats.samples = st.samples;
  stats.aa_mode = st.aa_mode;
  stats.color_buffer_bytes = pixels * S * 4;
  stats.depth_buffer_bytes = pixels * S * uint64_t((st.depth_bits + 7) / 8);
  stats.resolve_bytes = S > 1 ? pixels * S * 4 + pixels * 4 : 0;
}

void check_2d_sample_count(const Command& cmd, const RasterState& st) {
  if (st.samples == 1) return;
  if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body))
    throw SceneError(cmd.loc.str() + ": '" + d2->keyword + "' (2D drawing) with raster.samples = " +
                     std::to_string(st.samples) + ": the 2D engine writes pixels, not samples; draw 2D with "
                     "raster.samples = 1 (docs/antialiasing.md)");
}

void reject_2d_commands(const Scene& scene, const char* level) {
  for (const Command& cmd : scene.commands)
    if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body))
      throw SceneError(cmd.loc.str() + ": '" + d2->keyword + "' (2D drawing) is not supported by the " + level +
                       " level yet; `rastsim render` draws it (docs/2d.md)");
}

void count_interp_error(const Fragment& got, const Fragment& exact, RenderStats& stats) {
  const auto d = [](uint32_t a, uint32_t b) { return a > b ? a - b : b - a; };
  for (uint32_t e : {d(got.r, exact.r), d(got.g, exact.g), d(got.b, exact.b)}) {
    stats.max_attr_error_lsb = std::max(stats.max_attr_error_lsb, e);
    stats.attr_error_sum += e;
  }
  const uint32_t ez = d(got.z, exact.z);
  stats.max_depth_error_lsb = std::max(stats.max_depth_error_lsb, ez);
  stats.depth_error_sum += ez;
}

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

struct SceneRenderer::Impl {
  double seconds = 0;  // spent in the pipeline (constructor, run, finish): parsing excluded
  RasterState st;
  RenderStats& stats;
  FragmentSink on_fragment;
  Framebuffer fb;
  int F;
  TraversalParams tp;
  std::optional<CoverageCheck> check;       // only an inexact method is measured against the exact coverage
  std::vector<std::pair<int, int>> pixels;  // one triangle's, for the check

  Impl(const RasterState& arch, RenderStats& s, const FragmentSink& sink, int fb_tile_log2)
      : st(arch), stats(s), on_fragment(sink), fb(st.fb_width, st.fb_height, st.samples, fb_tile_log2),
        F(st.coord_format.frac_bits), tp(traversal_params(st)) {
    count_multisample_footprint(st, stats);
    fb.clear_depth(static_cast<uint32_t>((uint64_t{1} << st.depth_bits) - 1));
    stats.traversal_method = tp.method;
    if (!traversal_is_exact(tp.method)) check.emplace(st.fb_width, st.fb_height);
  }
  void run(const Command& cmd);
};

SceneRenderer::SceneRenderer(const RasterState& arch, RenderStats& stats, const FragmentSink& on_fragment,
                             int fb_tile_log2)
    : impl_(nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  impl_ = std::make_unique<Impl>(arch, stats, on_fragment, fb_tile_log2);
  impl_->seconds += seconds_since(t0);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::run(std::span<const Command> commands) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const Command& cmd : commands) impl_->run(cmd);
  impl_->seconds += seconds_since(t0);
}

void SceneRenderer::Impl::run(const Command& cmd) {
  Impl& m = *this;
  RenderStats& stats = m.stats;
  if (apply_state_command(cmd, m.st, m.fb)) return;
  if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body)) {
    check_2d_sample_count(cmd, m.st);
    draw_2d(*d2, cmd.loc, m.st, m.fb, stats.draw2d);
    return;
  }
  const auto& prims = std::get<CmdPrimitives>(cmd.body);
  const size_t n = triangle_count(prims);
  for (size_t k = 0; k < n; ++k) {
    ++stats.triangles_in;
    SetupTriangle tri;
    if (!count_setup_outcome(setup_triangle(assemble_triangle(prims, k), m.st, cmd.loc, tri), stats)) continue;
    m.pixels.clear();
    traverse(tri, m.tp, stats.traversal, [&](int px, int py, uint32_t mask) {
      if (m.check) m.pixels.emplace_back(px, py);
      shade_pixel(tri, px, py, mask, m.F, [&](const Fragment& f) {
        if (tri.interp_method != InterpMethod::Plane) count_interp_error(f, interpolate_plane(tri, px, py, m.F), stats);
        ++stats.fragments_shaded;
        if (m.on_fragment) m.on_fragment(f);
        if (rop_write(m.fb, f, m.st.depth_func, m.st.depth_write, &stats.samples_passed)) ++stats.fragments_passed;
      });
    });
    if (m.check) m.check->add_triangle(tri, m.F, m.pixels, stats.coverage);
  }
}

Framebuffer SceneRenderer::finish() {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  if (m.check) m.check->finish(m.stats.coverage);
  if (m.fb.samples > 1) m.fb = m.fb.resolve();  // the frame-end resolve pass
  m.stats.framebuffer_crc32 = m.fb.color_crc32();
  m.stats.wall_seconds = m.seconds + seconds_since(t0);
  return std::move(m.fb);
}

Framebuffer render_scene(const Scene& scene, const RasterState& arch, RenderStats& stats,
                         const FragmentSink& on_fragment, int fb_tile_log2) {
  SceneRenderer r(arch, stats, on_fragment, fb_tile_log2);
  r.run(scene.commands);
  return r.finish();
}

std::string fragment_trace_line(const Fragment& f) {
  std::string line = std::to_string(f.x) + " " + std::to_string(f.y) + " " + std::to_string(f.z) + " " +
                     std::to_string(f.r) + " " + std::to_string(f.g) + " " + std::to_string(f.b);
  if (f.samples > 1) line += " " + std::to_string(f.mask);
  return line;
}

}  // namespace rastsim
