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

Framebuffer render_scene(const Scene& scene, const RasterState& arch, RenderStats& stats,
                         const FragmentSink& on_fragment, int fb_tile_log2) {
  const auto t0 = std::chrono::steady_clock::now();
  RasterState st = arch;
  Framebuffer fb(st.fb_width, st.fb_height, st.samples, fb_tile_log2);
  count_multisample_footprint(st, stats);
  fb.clear_depth(static_cast<uint32_t>((uint64_t{1} << st.depth_bits) - 1));
  const int F = st.coord_format.frac_bits;
  const TraversalParams tp = traversal_params(st);
  stats.traversal_method = tp.method;
  // Only an inexact method is measured against the exact coverage.
  std::optional<CoverageCheck> check;
  if (!traversal_is_exact(tp.method)) check.emplace(st.fb_width, st.fb_height);
  std::vector<std::pair<int, int>> pixels;  // one triangle's, for the check
  for (const Command& cmd : scene.commands) {
    if (apply_state_command(cmd, st, fb)) continue;
    if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body)) {
      check_2d_sample_count(cmd, st);
      draw_2d(*d2, cmd.loc, st, fb, stats.draw2d);
      continue;
    }
    const auto& prims = std::get<CmdPrimitives>(cmd.body);
    const size_t n = triangle_count(prims);
    for (size_t k = 0; k < n; ++k) {
      ++stats.triangles_in;
      SetupTriangle tri;
      if (!count_setup_outcome(setup_triangle(assemble_triangle(prims, k), st, cmd.loc, tri), stats)) continue;
      pixels.clear();
      traverse(tri, tp, stats.traversal, [&](int px, int py, uint32_t mask) {
        if (check) pixels.emplace_back(px, py);
        shade_pixel(tri, px, py, mask, F, [&](const Fragment& f) {
          if (tri.interp_method != InterpMethod::Plane) count_interp_error(f, interpolate_plane(tri, px, py, F), stats);
          ++stats.fragments_shaded;
          if (on_fragment) on_fragment(f);
          if (rop_write(fb, f, st.depth_func, st.depth_write, &stats.samples_passed)) ++stats.fragments_passed;
        });
      });
      if (check) check->add_triangle(tri, F, pixels, stats.coverage);
    }
  }
  if (check) check->finish(stats.coverage);
  if (fb.samples > 1) fb = fb.resolve();  // the frame-end resolve pass
  stats.framebuffer_crc32 = fb.color_crc32();
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return fb;
}

std::string fragment_trace_line(const Fragment& f) {
  std::string line = std::to_string(f.x) + " " + std::to_string(f.y) + " " + std::to_string(f.z) + " " +
                     std::to_string(f.r) + " " + std::to_string(f.g) + " " + std::to_string(f.b);
  if (f.samples > 1) line += " " + std::to_string(f.mask);
  return line;
}

}  // namespace rastsim
