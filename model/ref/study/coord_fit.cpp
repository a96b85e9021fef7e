// SPDX-License-Identifier: Apache-2.0
#include "ref/study/coord_fit.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/tri_setup.h"

namespace rastsim {

namespace {

FixedFormat widest_with(int int_bits) { return FixedFormat{int_bits, kMaxFormatBits - int_bits}; }

// Walks the scene's state commands (viewport, scissor) as render_scene does and calls
// on_tri(state, triangle vertices, loc) for every assembled triangle (a clip-space
// command's out of the front end).
template <class OnTri>
void for_each_scene_triangle(const Scene& scene, RasterState st, OnTri&& on_tri) {
  FrontEndStats front_end;  // not reported
  Framebuffer scratch(1, 1);  // clears land here; only the state matters
  for (const Command& cmd : scene.commands) {
    const auto state = [&] { apply_state_command(cmd, st, scratch); };
    visit_command(cmd, Overloaded{
        state_commands(state),
        [&](const CmdPrimitives& prims) {
          for_each_triangle(prims, st, cmd.loc, front_end, [&](const ScreenTriangle& v) { on_tri(st, v, cmd.loc); });
        },
        [](const CmdDraw2d&) {},  // no triangle vertices
    });
  }
}

}  // namespace

RenderSignature render_signature(const Scene& scene, const RasterState& arch) {
  RasterState st = arch;
  st.out_of_range = OutOfRange::Error;
  RenderSignature sig;
  uLong crc = crc32(0L, Z_NULL, 0), cov = crc;
  try {
    RenderStats stats;
    const Framebuffer fb = render_scene(scene, st, stats, [&](const Fragment& f) {
      const std::string line = fragment_trace_line(f) + "\n";
      crc = crc32(crc, reinterpret_cast<const Bytef*>(line.data()), static_cast<uInt>(line.size()));
      const std::string xy = std::to_string(f.x) + " " + std::to_string(f.y) + "\n";
      cov = crc32(cov, reinterpret_cast<const Bytef*>(xy.data()), static_cast<uInt>(xy.size()));
      ++sig.fragments;
    });
    sig.color_crc32 = fb.color_crc32();
    sig.fragments_crc32 = static_cast<uint32_t>(crc);
    sig.coverage_crc32 = static_cast<uint32_t>(cov);
    sig.ok = true;
  } catch (const std::exception& e) {
    sig.error = e.what();
  }
  return sig;
}

Scene snap_scene_to_integer_pixels(const Scene& scene, const RasterState& arch) {
  Scene out = scene;
  RasterState st = arch;
  Framebuffer scratch(1, 1);  // clears land here; only the state matters
  FrontEndStats front_end;    // not reported
  const auto snap = [&](CmdPrimitives& prims, const SourceLoc& loc) {
    if (prims.clip_space()) {  // the front end's screen-space triangles, as a list
      CmdPrimitives screen;
      for_each_triangle(prims, st, loc, front_end, [&](const ScreenTriangle& v) {
        screen.vertices.insert(screen.vertices.end(), v.begin(), v.end());
      });
      prims = std::move(screen);
    }
    for (SceneVertex& v : prims.vertices) {
      if (v.x.saturated() || v.y.saturated()) continue;  // stays out of range for every format
      v.x.q = shift_right_round(v.x.q, Q64::kFracBits, Rounding::NearestEven) << Q64::kFracBits;
      v.y.q = shift_right_round(v.y.q, Q64::kFracBits, Rounding::NearestEven) << Q64::kFracBits;
    }
  };
  for (Command& cmd : out.commands)  // std::visit, not visit_command: the command changes in place
    std::visit(Overloaded{
        state_commands([&] { apply_state_command(cmd, st, scratch); }),
        [&](CmdPrimitives& prims) { snap(prims, cmd.loc); },
        [](const CmdDraw2d&) {},  // 2D drawing keeps its coordinates
    }, cmd.body);
  return out;
}

int int_bits_for_viewports(const Scene& scene, const RasterState& arch) {
  int64_t need = std::max(arch.viewport_width, arch.viewport_height);
  for (const Command& cmd : scene.commands)
    visit_command(cmd, Overloaded{
        [&](const CmdViewport& vp) { need = std::max<int64_t>(need, std::max(vp.width, vp.height)); },
        [](const CmdClear&) {},
        [](const CmdClearDepth&) {},
        [](const CmdScissor&) {},
        [](const CmdPrimitives&) {},
        [](const CmdDraw2d&) {},
    });
  for (int i = 0; i < kMaxFormatBits; ++i)
    if (max_viewport_extent(widest_with(i)) >= need) return i;
  throw SceneError(scene.source + ": a viewport side of " + std::to_string(need) + " px fits no coordinate format");
}

int int_bits_for_vertices(const Scene& scene, const RasterState& arch) {
  int need = 0;
  RasterState st = arch;
  st.coord_format = widest_with(kMaxFormatBits - 1);  // s30.1: no viewport check fails on the walk
  for_each_scene_triangle(scene, st, [&](const RasterState& s, const std::array<SceneVertex, 3>& v, const SourceLoc& loc) {
    for (int k = 0; k < 3; ++k) {
      // Raise I until this vertex snaps inside s I.(31-I) (range [-2^I, 2^I - 2^-(31-I)]).
      while (need < kMaxFormatBits &&
             !(snap_coord(v[k].x, s.origin_x(), widest_with(need)) && snap_coord(v[k].y, s.origin_y(), widest_with(need))))
        ++need;
      if (need == kMaxFormatBits)
        throw SceneError(loc.str() + ": vertex " + std::to_string(k) + " (" + std::to_string(v[k].x.to_double()) +
                         ", " + std::to_string(v[k].y.to_double()) + ") fits no coordinate format (I <= " +
                         std::to_string(kMaxFormatBits - 1) + ")");
    }
  });
  return need;
}

CoordFit fit_coord_format(const Scene& scene, const RasterState& arch) {
  CoordFit fit;
  fit.int_bits_viewport = int_bits_for_viewports(scene, arch);
  fit.int_bits_vertices = int_bits_for_vertices(scene, arch);
  const int I = std::max(fit.int_bits_viewport, fit.int_bits_vertices);
  fit.widest = widest_with(I);
  RasterState st = arch;
  st.coord_format = fit.widest;
  fit.reference = render_signature(scene, st);
  if (!fit.reference.ok)
    throw SceneError("the reference render in " + fit.widest.name() + " fails: " + fit.reference.error);
  // Scan F upward: the first identical render is the fit, so F - 1 differs by construction.
  for (int F = 1; F <= fit.widest.frac_bits; ++F) {
    st.coord_format = FixedFormat{I, F};
    const RenderSignature sig = F == fit.widest.frac_bits ? fit.reference : render_signature(scene, st);
    const bool cov = sig.ok && sig.coverage_crc32 == fit.reference.coverage_crc32 &&
                     sig.fragments == fit.reference.fragments;
    const bool color = sig.ok && sig.color_crc32 == fit.reference.color_crc32;
    fit.trials.push_back({F, sig.same_as(fit.reference), cov, color, sig.error});
    if (cov && !fit.coverage_frac_bits) fit.coverage_frac_bits = F;
    if (color && !fit.color_frac_bits) fit.color_frac_bits = F;
    if (sig.same_as(fit.reference)) {
      fit.format = st.coord_format;
      fit.fitted = sig;
      break;
    }
  }
  fit.widths = datapath_widths(fit.format, arch.depth_bits);
  if (fit.format.frac_bits == 1) {
    st.coord_format = FixedFormat{I, 1};
    fit.exact_at_zero_frac = render_signature(snap_scene_to_integer_pixels(scene, st), st).same_as(fit.reference);
  }
  return fit;
}

bool is_closed_mesh(const Scene& scene) {
  // Undirected edge (by exact vertex position) -> (uses, sum of directions).
  using Pt = std::pair<i128, i128>;
  std::map<std::pair<Pt, Pt>, std::pair<int, int>> edges;
  size_t triangles = 0;
  const auto add_edges = [&](const CmdPrimitives& prims) {
    for (size_t k = 0; k < triangle_count(prims); ++k) {
      const auto v = assemble_triangle(prims, k);
      ++triangles;
      for (int i = 0; i < 3; ++i) {
        Pt p{v[i].x.q, v[i].y.q}, q{v[(i + 1) % 3].x.q, v[(i + 1) % 3].y.q};
        const int dir = p < q ? 1 : -1;
        auto& e = edges[p < q ? std::make_pair(p, q) : std::make_pair(q, p)];
        ++e.first;
        e.second += dir;
      }
    }
  };
  bool clip_space = false;
  for (const Command& cmd : scene.commands)
    visit_command(cmd, Overloaded{
        state_commands([] {}),
        [&](const CmdPrimitives& prims) {
          clip_space = clip_space || prims.clip_space();
          add_edges(prims);
        },
        [](const CmdDraw2d&) {},  // the triangles' mesh only
    });
  if (triangles == 0 || clip_space) return false;
  for (const auto& [key, e] : edges)
    if (e.first != 2 || e.second != 0) return false;
  return true;
}

uint64_t unbalanced_pixels(const Scene& scene, const RasterState& arch) {
  RasterState st = arch;
  st.cull = CullMode::None;
  st.out_of_range = OutOfRange::Cull;
  std::vector<int> signed_cover(size_t(st.fb_width) * st.fb_height, 0);
  const int F = st.coord_format.frac_bits;
  for_each_scene_triangle(scene, st, [&](const RasterState& s, const std::array<SceneVertex, 3>& v, const SourceLoc& loc) {
    SetupTriangle t;
    if (setup_triangle(v, s, loc, t) != SetupOutcome::Accepted) return;
    const int w = t.ccw_on_screen ? -1 : 1;
    for (int py = t.bbox.y0; py < t.bbox.y1; ++py)
      for (int px = t.bbox.x0; px < t.bbox.x1; ++px) {
        const int64_t x = t.sample_x(px, F), y = t.sample_y(py, F);
        bool in = true;
        for (const EdgeEq& e : t.edge) in = in && e.eval(x, y) + e.bias >= 0;
        if (in) signed_cover[size_t(py) * st.fb_width + px] += w;
      }
  });
  return uint64_t(std::count_if(signed_cover.begin(), signed_cover.end(), [](int c) { return c != 0; }));
}

std::vector<PrecisionRow> measure_precision(const Scene& scene, const RasterState& arch, int int_bits, int max_frac) {
  const bool closed = is_closed_mesh(scene);
  const Scene integer_scene = snap_scene_to_integer_pixels(scene, arch);
  auto render = [&](int F, Framebuffer& fb) -> std::string {
    RasterState st = arch;
    st.out_of_range = OutOfRange::Error;
    st.coord_format = FixedFormat{int_bits, std::max(F, 1)};
    try {
      RenderStats stats;
      fb = render_scene(F == 0 ? integer_scene : scene, st, stats);
      return {};
    } catch (const std::exception& e) {
      return e.what();
    }
  };
  Framebuffer golden;
  const std::string golden_error = render(max_frac, golden);
  if (!golden_error.empty()) throw SceneError("the " + FixedFormat{int_bits, max_frac}.name() + " render fails: " + golden_error);
  std::vector<PrecisionRow> rows;
  for (int F = 0; F <= max_frac; ++F) {
    PrecisionRow r;
    r.frac_bits = F;
    r.format = FixedFormat{int_bits, std::max(F, 1)};
    r.edge_width = datapath_widths(r.format, arch.depth_bits).edge;
    Framebuffer fb;
    r.error = render(F, fb);
    r.ok = r.error.empty();
    if (r.ok) {
      std::vector<uint8_t> row(size_t(fb.width) * 4), golden_row(row.size());
      for (int y = 0; y < fb.height; ++y) {
        fb.read_row(y, row.data());
        golden.read_row(y, golden_row.data());
        for (size_t p = 0; p < row.size(); p += 4)
          r.pixels_different += !std::equal(&row[p], &row[p] + 4, &golden_row[p]);
      }
      if (closed) {
        RasterState st = arch;
        st.coord_format = r.format;
        r.cracks = unbalanced_pixels(F == 0 ? integer_scene : scene, st);
      }
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

RecipFit fit_recip(const Scene& scene, const RasterState& arch) {
  RecipFit fit;
  for_each_scene_triangle(scene, arch, [&](const RasterState& st, const ScreenTriangle& v, const SourceLoc& loc) {
    SetupTriangle tri;
    if (setup_triangle(v, st, loc, tri) != SetupOutcome::Accepted) return;
    ++fit.triangles;
    if (!tri.affine) ++fit.perspective_triangles;
    for (const SceneVertex& c : v) fit.max_abs_texcoord = std::max({fit.max_abs_texcoord, std::fabs(double(c.s)), std::fabs(double(c.t))});
  });
  while (std::ldexp(1.0, fit.texcoord_int_bits) <= fit.max_abs_texcoord) ++fit.texcoord_int_bits;
  if (fit.perspective_triangles == 0) return fit;  // no reciprocal taken: nothing to scan
  RasterState st = arch;
  st.recip = RecipMethod::Exact;
  fit.exact = render_signature(scene, st);
  if (!fit.exact.ok) throw SceneError("the reference render (interp.recip = exact) fails: " + fit.exact.error);
  st.recip = RecipMethod::Newton;
  for (int it = 0; it <= kRecipFitIterations; ++it) {
    st.recip_iterations = it;
    for (int b = 1; b <= 16 && !fit.seed_bits[size_t(it)]; ++b) {
      st.recip_seed_bits = b;
      if (render_signature(scene, st).same_as(fit.exact)) fit.seed_bits[size_t(it)] = b;
    }
  }
  return fit;
}

}  // namespace rastsim
