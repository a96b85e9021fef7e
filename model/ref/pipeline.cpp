// SPDX-License-Identifier: Apache-2.0
#include "ref/pipeline.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>

#include "ref/homogeneous.h"
#include "ref/prim_assembly.h"
#include "ref/region_bins.h"
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

namespace {
// Of the fragments that fail the late test (culled or tested and written nowhere), the
// fraction `removed`; 1 when none fails.
double fraction_of_failures(const RenderStats& s, uint64_t removed) {
  const uint64_t failed = s.hiz.fragments_culled + s.fragments_culled_early + (s.fragments_shaded - s.fragments_passed);
  return failed ? double(removed) / double(failed) : 1.0;
}
}  // namespace

double hiz_oracle_fraction(const RenderStats& s) {
  return fraction_of_failures(s, s.hiz.fragments_culled + s.fragments_culled_early);
}
double hiz_culled_fraction(const RenderStats& s) { return fraction_of_failures(s, s.hiz.fragments_culled); }

namespace {
void apply_viewport(const CmdViewport& c, const SourceLoc& loc, RasterState& st) {
  const int64_t max_extent = max_viewport_extent(st.coord_format);
  if (c.width < 1 || c.height < 1 || c.width > st.fb_width || c.height > st.fb_height)
    throw SceneError(loc.str() + ": viewport " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                     " does not fit the " + std::to_string(st.fb_width) + "x" + std::to_string(st.fb_height) +
                     " framebuffer (display.width x display.height)");
  if (c.width > max_extent || c.height > max_extent)
    throw SceneError(loc.str() + ": viewport " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                     " does not fit raster.coord_format " + st.coord_format.name() + " (largest " +
                     std::to_string(max_extent) + " px)");
  st.viewport_width = c.width;
  st.viewport_height = c.height;
}

}  // namespace

uint32_t clear_depth_value(const CmdClearDepth& c, const SourceLoc& loc, const RasterState& st) {
  const auto z = quantize_unorm(c.z, st.depth_bits);
  if (!z) throw SceneError(loc.str() + ": clear depth must be in [0, 1]");
  return *z;
}

bool apply_state_command(const Command& cmd, RasterState& st, Framebuffer& fb, RopMemory* mem) {
  return visit_command(cmd, Overloaded{
      [&](const CmdViewport& c) {
        apply_viewport(c, cmd.loc, st);
        return true;
      },
      [&](const CmdClear& c) {
        fb.clear_color(c.r, c.g, c.b);
        if (mem) mem->clear_color();
        return true;
      },
      [&](const CmdClearDepth& c) {
        fb.clear_depth(clear_depth_value(c, cmd.loc, st));
        if (mem) mem->clear_depth();
        return true;
      },
      [&](const CmdScissor& c) {
        st.scissor_enabled = c.enabled;
        st.scissor = {c.x, c.y, c.x + c.width, c.y + c.height};
        return true;
      },
      [](const CmdPrimitives&) { return false; },  // drawing, not state
      [](const CmdDraw2d&) { return false; },
  });
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

// The stats drawing a triangle adds (traversal onwards); a worker of the parallel path
// counts into its own RenderStats and they are added up after each chunk.
void add_draw_stats(RenderStats& into, const RenderStats& part) {
  into.traversal += part.traversal;
  for (auto m : {&RenderStats::fragments_shaded, &RenderStats::fragments_passed, &RenderStats::samples_passed,
                 &RenderStats::depth_writes, &RenderStats::fragments_culled_early, &RenderStats::interpolations_saved,
                 &RenderStats::texture_samples_saved, &RenderStats::attr_error_sum, &RenderStats::depth_error_sum})
    into.*m += part.*m;
  for (auto m : {&RenderStats::max_attr_error_lsb, &RenderStats::max_depth_error_lsb})
    into.*m = std::max(into.*m, part.*m);
}
}  // namespace

struct SceneRenderer::Impl {
  // The SpanEmitter (fine_raster.h) of draw()'s run path: a one-sample triangle whose
  // fragments PixelShader::shade_run gives, written by rop_write_run.
  struct RunWriter {
    Impl& m;
    PixelShader& shader;
    RenderStats& s;
    void operator()(int px, int py, uint32_t mask) { span(py, px, px + 1, mask); }
    void span(int py, int x0, int x1, uint32_t) {
      const uint32_t n = shader.shade_run(py, x0, [&](auto&& frag) {
        return rop_write_run(m.fb, py, x0, x1, frag, m.st.depth_func, m.st.depth_write, m.mem_ptr());
      });
      s.fragments_shaded += uint64_t(x1 - x0);
      s.fragments_passed += n;
      m.count_written(s, n);
    }
  };

  double seconds = 0;  // spent in the pipeline (constructor, run, finish): parsing excluded
  RasterState st;
  RenderStats& stats;
  FragmentSink on_fragment;
  Framebuffer fb;
  int F;
  TraversalParams tp;
  std::optional<CoverageCheck> check;       // only an inexact method is measured against the exact coverage
  std::vector<std::pair<int, int>> pixels;  // one triangle's, for the check
  // The parallel path (threads > 1): regions, and one chunk of set-up triangles binned.
  int threads = 1;
  RegionGrid grid;
  std::vector<SetupTriangle> tris;
  std::vector<SetupOutcome> outcomes;
  std::vector<std::pair<ScreenTriangle, const SourceLoc*>> chunk;  // assembled triangles of a run of primitives
  std::vector<std::vector<uint32_t>> bins;              // per region: indices into tris, in order
  std::optional<RopMemory> mem;  // the functional memory system, when on
  std::optional<HizTable> hiz;   // the Hi-Z bound table, when hiz_applies
  HizObserver hiz_observer;
  // The depth function the ROP tests the current tile's fragments with: the state's, or
  // `always` in a tile Hi-Z accepted (every fragment passes: no depth read).
  DepthFunc tile_func = DepthFunc::Always;
  std::optional<Binner> binner;  // pipeline.mode = binned
  // pipeline.mode = binned with memory.model != fixed: the binning and tile_store clients
  // (the ROP writes the tile buffer, so `mem` stays off).
  std::optional<BinMemory> bin_mem;

  RopMemory* mem_ptr() { return mem ? &*mem : nullptr; }
  // The binned clients' counts into stats.memory (with bin_mem).
  void bin_memory_stats() {
    if (!bin_mem) return;
    stats.memory.enabled = stats.memory.binned = true;
    stats.memory.binning = bin_mem->binning_stats();
    stats.memory.tile_store = bin_mem->tile_store_stats();
  }

  Impl(const RasterState& arch, RenderStats& s, const FragmentSink& sink, int fb_tile_log2, int n_threads,
       const MemoryParams& memory)
      : st(arch), stats(s), on_fragment(sink), fb(st.fb_width, st.fb_height, st.samples, fb_tile_log2),
        F(st.coord_format.frac_bits), tp(traversal_params(st)),
        grid(st.fb_width, st.fb_height,
             {tp.method == Traversal::Tiled ? tp.tile_size : 1,
              tp.method == Traversal::Hierarchical && !tp.hier_levels.empty() ? tp.hier_levels[0] : 1,
              fb.tile_size()}) {
    count_multisample_footprint(st, stats);
    stats.depth_early = st.depth_early;
    stats.hiz_mode = st.hiz_mode;
    tile_func = st.depth_func;
    const bool binned = st.bin.mode == PipelineMode::Binned;
    if (memory.enabled && !binned) mem.emplace(memory, fb, st.depth_bits);
    if (memory.enabled && binned)
      bin_mem.emplace(memory, st.fb_width, st.fb_height, st.samples, st.depth_bits, st.bin.parameter_buffer_base,
                      st.bin.parameter_buffer_bytes);
    if (hiz_applies(st)) {
      hiz.emplace(st.hiz_mode, st.hiz_block, st.hiz_bytes, st.fb_width, st.fb_height, st.depth_bits);
      hiz->dram_base = st.hiz_base;  // the addresses the timed model's client uses
    }
    // The frame starts with depth cleared to 1.0 (a clear the memory system sees); the
    // colour buffer's initial black is taken to be in memory already.
    fb.clear_depth(static_cast<uint32_t>((uint64_t{1} << st.depth_bits) - 1));
    if (mem) mem->clear_depth();
    stats.traversal_method = tp.method;
    if (!traversal_is_exact(tp.method)) check.emplace(st.fb_width, st.fb_height);
    // One thread where the result depends on the order of the whole walk: the fragment
    // stream (pipeline order), the coverage check of an inexact method (per triangle) and
    // the memory system's access stream.
    if (binned)
      binner.emplace(
          st, tp, fb, [this](const SetupTriangle& tri, const SetupTriangle& walk) { draw(tri, walk, stats); },
          stats.bin, bin_mem ? &*bin_mem : nullptr);
    threads = (on_fragment || check || mem || hiz || binner) ? 1 : std::max(1, n_threads);
    if (threads > 1) bins.resize(size_t(grid.count()));
  }
  void run(const Command& cmd);
  void run_binned(const Command& cmd);
  void draw_triangles(const Command& cmd, const CmdPrimitives& prims);
  void run_parallel(std::span<const Command> commands);
  void draw_primitives(std::span<const Command> commands);
  void draw_chunk();

  // Traverses `walk` (tri itself, or tri with its box clipped to a region) and shades,
  // tests and writes every fragment of tri, counting into s.
  void draw(const SetupTriangle& tri, const SetupTriangle& walk, RenderStats& s) {
    PixelShader shader(tri, F);  // PlaneStepper where it applies
    if (hiz) {  // Hi-Z: the tiled walk with the bound table's test, one fragment at a time
      traverse_triangle(walk, tp.tile_size, F, s.traversal, [&](int px, int py, uint32_t mask) {
        if (check) pixels.emplace_back(px, py);
        shader.shade(px, py, mask, [&](const Fragment& f) { write(tri, px, py, f, s, false, [](const Fragment& g) { return g; }); });
      }, HizFilter{*this, tri});
      return;
    }
    if (shader.stepped() && !check && !on_fragment && !st.depth_early) {
      // One fragment a covered pixel, no error stats to add and nobody watching the
      // fragments: traversal's runs of pixels are shaded and written a run at a time
      // (rop_write_run: the same writes as rop_write on each fragment in turn).
      RunWriter w{*this, shader, s};
      traverse(walk, tp, s.traversal, w);
      return;
    }
    traverse(walk, tp, s.traversal, [&](int px, int py, uint32_t mask) {
      if (check) pixels.emplace_back(px, py);
      shader.shade(px, py, mask, [&](const Fragment& f) { write(tri, px, py, f, s, false, [](const Fragment& g) { return g; }); });
    });
  }

  // One fragment of pixel (px, py) of tri out of interpolation: with depth.early, culled
  // here when it fails the depth test at every sample (the colour and, when `textured`,
  // texture work it saves counted); else counted, shown to the fragment sink, then
  // `texture(f)` (the texture stage, or f itself) tested and written. The reference
  // interpolates every attribute at once: the early test uses the same depth a pipeline
  // interpolating depth first would (docs/depth.md).
  template <class TextureStage>
  void write(const SetupTriangle& tri, int px, int py, const Fragment& f, RenderStats& s, bool textured,
             TextureStage&& texture) {
    if (tri.interp_method != InterpMethod::Plane) count_interp_error(f, interpolate_plane(tri, px, py, F), s);
    if (st.depth_early && early_depth_cull(fb, f, tile_func, mem_ptr())) {
      ++s.fragments_culled_early;
      s.interpolations_saved += early_interpolations_saved(textured);
      s.texture_samples_saved += textured ? 1 : 0;
      return;
    }
    ++s.fragments_shaded;
    if (on_fragment) on_fragment(f);
    rop(texture(f), s);
  }
  // The ROP: f tested and written, counted into s.
  void rop(const Fragment& f, RenderStats& s) {
    uint64_t n = 0;
    if (rop_write(fb, f, tile_func, st.depth_write, &n, mem_ptr())) {
      ++s.fragments_passed;
      if (hiz && st.depth_write) hiz->write(f.x, f.y, f.z);  // one sample (hiz_applies)
    }
    count_written(s, n);
  }

  // traverse_triangle's tile filter with Hi-Z: each tile coarse raster did not reject
  // tested against the bound table with its conservative depth range; a culled tile's
  // covered pixels counted (the oracle score's), an accepted one's fragments tested with
  // `always`; the table's blocks the tile wrote flushed at its end.
  struct HizFilter {
    Impl& m;
    const SetupTriangle& tri;
    bool operator()(const PixelRect& fp, TileClass cls) {
      const HizDecision d = m.hiz->test(fp, tile_depth_range(tri, fp, m.F), m.st.depth_func);
      if (m.hiz_observer && d != HizDecision::Draw) m.hiz_observer({tri, fp, d, m.fb, m.st.depth_func});
      if (d == HizDecision::Culled) {
        uint64_t n = 0;
        if (cls == TileClass::Accepted) n = uint64_t(fp.area());
        else fine_raster_partial(tri, fp, m.F, [&](int, int, uint32_t) { ++n; });
        m.hiz->stats.fragments_culled += n;
        return false;
      }
      m.tile_func = d == HizDecision::Accepted ? DepthFunc::Always : m.st.depth_func;
      return true;
    }
    void done() {
      m.hiz->flush();
      m.tile_func = m.st.depth_func;
    }
  };
  // n samples written by the ROP: their colour and, with raster.depth_write, their depth.
  void count_written(RenderStats& s, uint64_t n) const {
    s.samples_passed += n;
    if (st.depth_write) s.depth_writes += n;
  }

  // The texture stage (ref/texture/texture_unit.h, docs/texture.md): created at the first
  // textured triangle; its quads' derivatives, one triangle's.
  std::optional<TextureUnit> tex;
  TriangleQuads quads;
  void draw_textured(const SetupTriangle& tri, const TextureState& ts);
};

SceneRenderer::SceneRenderer(const RasterState& arch, RenderStats& stats, const FragmentSink& on_fragment,
                             int fb_tile_log2, int threads, const MemoryParams& memory)
    : impl_(nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  impl_ = std::make_unique<Impl>(arch, stats, on_fragment, fb_tile_log2, threads, memory);
  impl_->seconds += seconds_since(t0);
}

SceneRenderer::~SceneRenderer() = default;

int SceneRenderer::threads() const { return impl_->threads; }

void SceneRenderer::set_hiz_observer(HizObserver observer) { impl_->hiz_observer = std::move(observer); }

void SceneRenderer::run(std::span<const Command> commands) {
  const auto t0 = std::chrono::steady_clock::now();
  if (impl_->threads > 1) impl_->run_parallel(commands);
  else
    for (const Command& cmd : commands) impl_->run(cmd);
  impl_->seconds += seconds_since(t0);
}

void SceneRenderer::Impl::run(const Command& cmd) {
  if (binner) return run_binned(cmd);
  const auto state = [&] {
    apply_state_command(cmd, st, fb, mem_ptr());
    if (hiz && std::holds_alternative<CmdClearDepth>(cmd.body)) hiz->clear(fb.cleared_depth());  // exact bounds
  };
  visit_command(cmd, Overloaded{
      state_commands(state),
      [&](const CmdPrimitives& prims) { draw_triangles(cmd, prims); },
      [&](const CmdDraw2d& d2) {
        check_2d_sample_count(cmd, st);
        draw_2d(d2, cmd.loc, st, fb, stats.draw2d, mem ? &mem->color : nullptr);  // through the colour client
      },
  });
}

// pipeline.mode = binned: viewport and scissor applied now (setup, in the binning pass,
// clips each box to them); clears recorded in every bin's list; triangles binned.
void SceneRenderer::Impl::run_binned(const Command& cmd) {
  check_binned_command(cmd, st);
  if (const auto* c = std::get_if<CmdClear>(&cmd.body)) return binner->add_clear_color(c->r, c->g, c->b, cmd.loc);
  if (const auto* c = std::get_if<CmdClearDepth>(&cmd.body))
    return binner->add_clear_depth(clear_depth_value(*c, cmd.loc, st), cmd.loc);
  if (const auto* p = std::get_if<CmdPrimitives>(&cmd.body)) return draw_triangles(cmd, *p);
  apply_state_command(cmd, st, fb, nullptr);
}

// One primitives command's triangles on this thread, in order.
void SceneRenderer::Impl::draw_triangles(const Command& cmd, const CmdPrimitives& prims) {
  if (prims.texture.enabled() && draws_homogeneous(prims, st))
    throw SceneError(cmd.loc.str() + ": a texture is bound and clip.method = homogeneous: texturing is modelled "
                     "for clip.method = clip only");
  if (draws_homogeneous(prims, st)) {  // clip.method = homogeneous: no screen-space triangles
    const auto setup_done = [&](SetupOutcome o) {
      ++stats.triangles_in;
      return count_setup_outcome(o, stats);
    };
    draw_homogeneous(prims, st, cmd.loc, stats.front_end, stats.traversal, setup_done, [&](const Fragment& f) {
      ++stats.fragments_shaded;
      if (on_fragment) on_fragment(f);
      rop(f, stats);  // the late test only (docs/depth.md)
    });
    if (hiz) hiz->flush();  // its writes' blocks, once a command
    return;
  }
  for_each_triangle(prims, st, cmd.loc, stats.front_end, [&](const ScreenTriangle& v) {
    ++stats.triangles_in;
    SetupTriangle tri;
    if (!count_setup_outcome(setup_triangle(v, st, cmd.loc, tri), stats)) return;
    if (binner) return binner->add_triangle(tri, cmd.loc);
    pixels.clear();
    if (prims.texture.enabled()) draw_textured(tri, prims.texture);
    else draw(tri, tri, stats);
    if (check) check->add_triangle(tri, F, pixels, stats.coverage);
  });
}

// A textured triangle on this thread: every covered pixel's fragments through the
// texture stage with the derivatives of its 2x2 quad (pixels 2x..2x+1, 2y..2y+1); the
// quads' pixels not covered are helper pixels, shaded for the derivatives, never written.
void SceneRenderer::Impl::draw_textured(const SetupTriangle& tri, const TextureState& ts) {
  if (!tex) tex.emplace(st.texture);
  PixelShader shader(tri, F);
  quads.clear();
  const int tex_frac = st.texcoord_format.frac_bits;
  const auto emit = [&](int px, int py, uint32_t mask) {
    if (check) pixels.emplace_back(px, py);
    quads.add_covered(1);
    const QuadDerivatives& d = quads.derivatives(tri, px, py, F);
    shader.shade(px, py, mask, [&](const Fragment& f) {
      write(tri, px, py, f, stats, true, [&](const Fragment& g) { return tex->shade(g, d, ts, tex_frac); });
    });
  };
  if (hiz) traverse_triangle(tri, tp.tile_size, F, stats.traversal, emit, HizFilter{*this, tri});
  else traverse(tri, tp, stats.traversal, emit);
  tex->stats().helper_pixels += quads.helper_pixels();
}

// State and 2D commands one by one, in order; each run of primitive commands between
// them set up and rasterized in parallel (draw_primitives).
void SceneRenderer::Impl::run_parallel(std::span<const Command> commands) {
  size_t i = 0;
  while (i < commands.size()) {
    size_t j = i;
    while (j < commands.size() && std::holds_alternative<CmdPrimitives>(commands[j].body)) ++j;
    if (j == i) {
      run(commands[i++]);
      continue;
    }
    draw_primitives(commands.subspan(i, j - i));
    i = j;
  }
}

namespace {
// Triangles set up and binned at a time (memory: ~300 bytes each), and the fewest worth
// the threads (fewer go through the one-thread path, the same result).
constexpr size_t kChunkTriangles = 16384, kMinParallelTriangles = 256;
}  // namespace

void SceneRenderer::Impl::draw_primitives(std::span<const Command> commands) {
  size_t inputs = 0;  // triangles in (a clip-space command's before clipping): is the run worth the threads?
  // Drawn on this thread: homogeneous (ref/homogeneous.h: no screen triangles to bin) and
  // textured (the texture cache's access stream is in pipeline order).
  bool one_thread = false;
  for (const Command& cmd : commands) {
    const auto& p = std::get<CmdPrimitives>(cmd.body);
    inputs += p.clip_space() ? triangle_count(p.topology, p.clip_vertices.size()) : triangle_count(p);
    one_thread = one_thread || draws_homogeneous(p, st) || p.texture.enabled();
  }
  if (inputs < kMinParallelTriangles || one_thread) {
    for (const Command& cmd : commands) run(cmd);
    return;
  }
  // Assembled (and front-end) triangles in order, set up and drawn a chunk at a time.
  chunk.clear();
  for (const Command& cmd : commands)
    for_each_triangle(std::get<CmdPrimitives>(cmd.body), st, cmd.loc, stats.front_end, [&](const ScreenTriangle& v) {
      chunk.push_back({v, &cmd.loc});
      if (chunk.size() < kChunkTriangles) return;
      draw_chunk();
      chunk.clear();
    });
  if (!chunk.empty()) draw_chunk();
}

// The triangles of `chunk`: set up on `threads` contiguous slices (setup is per
// triangle), counted and binned in order, then the regions rasterized by `threads`
// workers taking the next region with a triangle. Counters are per tile, pixel or
// fragment and add up over regions, except the bbox method's one "tile" a triangle,
// counted in the region of its box's first pixel only.
void SceneRenderer::Impl::draw_chunk() {
  const size_t n = chunk.size();
  tris.resize(n);
  outcomes.resize(n);
  run_on_threads(threads, [&](int t) {
    const size_t k0 = n * size_t(t) / size_t(threads), k1 = n * size_t(t + 1) / size_t(threads);
    for (size_t k = k0; k < k1; ++k) {
      outcomes[k] = setup_triangle(chunk[k].first, st, *chunk[k].second, tris[k]);
    }
  });
  for (auto& b : bins) b.clear();
  for (size_t k = 0; k < n; ++k) {
    ++stats.triangles_in;
    if (!count_setup_outcome(outcomes[k], stats)) continue;
    const PixelRect r = grid.range(tris[k].bbox);
    for (int ry = r.y0; ry < r.y1; ++ry)
      for (int rx = r.x0; rx < r.x1; ++rx) bins[size_t(ry * grid.nx + rx)].push_back(uint32_t(k));
  }
  std::vector<RenderStats> part(static_cast<size_t>(threads));
  std::atomic<int> next{0};
  run_on_threads(threads, [&](int t) {
    RenderStats& s = part[size_t(t)];
    for (int r; (r = next.fetch_add(1, std::memory_order_relaxed)) < grid.count();) {
      const PixelRect rect = grid.rect(r);
      for (uint32_t k : bins[size_t(r)]) {
        const SetupTriangle& tri = tris[k];
        SetupTriangle walk = tri;
        walk.bbox = tri.bbox.intersect(rect);
        draw(tri, walk, s);
        if (tp.method == Traversal::Bbox && grid.region_of(tri.bbox.x0, tri.bbox.y0) != r) {
          --s.traversal.tiles_visited;  // the box is one tile: counted once, in its first region
          --s.traversal.tiles_partial;
        }
      }
    }
  });
  for (const RenderStats& s : part) add_draw_stats(stats, s);
}

const RopMemory* SceneRenderer::memory() const { return impl_->mem ? &*impl_->mem : nullptr; }

const Framebuffer& SceneRenderer::frame_so_far() {
  Impl& m = *impl_;
  if (m.mem) m.stats.memory = m.mem->stats();
  m.bin_memory_stats();
  if (m.tex) m.stats.texture = m.tex->stats();
  return m.fb;
}

Framebuffer SceneRenderer::finish() {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  if (m.binner) m.binner->finish();
  if (m.check) m.check->finish(m.stats.coverage);
  if (m.mem) {  // the resolve's reads, the caches' flush, the resolved image's writes
    m.mem->finish();
    m.stats.memory = m.mem->stats();
  }
  m.bin_memory_stats();
  if (m.tex) m.stats.texture = m.tex->stats();
  if (m.hiz) m.stats.hiz = m.hiz->stats;
  if (m.fb.samples > 1) m.fb = m.fb.resolve();  // the frame-end resolve pass
  m.stats.framebuffer_crc32 = m.fb.color_crc32();
  m.stats.wall_seconds = m.seconds + seconds_since(t0);
  return std::move(m.fb);
}

Framebuffer render_scene(const Scene& scene, const RasterState& arch, RenderStats& stats,
                         const FragmentSink& on_fragment, int fb_tile_log2, int threads,
                         const MemoryParams& memory) {
  SceneRenderer r(arch, stats, on_fragment, fb_tile_log2, threads, memory);
  r.run(scene.commands);
  return r.finish();
}

std::string fragment_trace_line(const Fragment& f) {
  // Appended, not chained operator+: GCC 12 at -O3 reports a false -Wrestrict on
  // operator+(const char*, string&&) (GCC bug 105329), which -Werror stops.
  std::string line = std::to_string(f.x);
  const auto field = [&](auto v) {
    line += ' ';
    line += std::to_string(v);
  };
  field(f.y);
  field(f.z);
  field(unsigned(f.r));
  field(unsigned(f.g));
  field(unsigned(f.b));
  field(f.s);
  field(f.t);
  if (f.samples > 1) field(unsigned(f.mask));
  return line;
}

}  // namespace rastsim
