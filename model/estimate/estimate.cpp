// SPDX-License-Identifier: Apache-2.0
#include "estimate/estimate.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <optional>

#include "config/raster_state_config.h"
#include "ref/framebuffer.h"
#include "ref/hiz.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/traverse.h"
#include "ref/tri_setup.h"
#include "report/stats_json.h"

namespace rastsim {

namespace {

// One pass over the scene in program order. Every stage of the timed model sees the
// transactions in program order and keeps no state that changes a cost except the
// raster state (viewport, scissor), which fetch and setup update at the same commands,
// so one walk of the commands with one RasterState gives every stage's transactions.
class Walker {
 public:
  Walker(const RasterState& arch, const TimingParams& p, EstimateResult& r)
      : st_(arch), tp_(traversal_params(arch)), p_(p), r_(r),
        fb_pixels_(uint64_t(arch.fb_width) * uint64_t(arch.fb_height)),
        depth_bytes_(uint64_t((arch.depth_bits + 7) / 8)) {
    r_.render.traversal_method = tp_.method;
    count_multisample_footprint(arch, r_.render);
    if (hiz_applies(arch)) hiz_.emplace(arch);
  }

  // After the last command, with raster.samples > 1: the end-of-frame marker (fetched
  // like a command header) and the ROP's resolve pass, as sc/command_fetch and sc/rop.
  void end_of_frame() {
    if (st_.samples == 1) return;
    work(StageId::CommandFetch, p_.fetch_header_cycles());
    r_.resolve_cycles = p_.resolve_cycles(fb_pixels_, st_.samples);
    r_.framebuffer_bytes += r_.render.resolve_bytes;
    marker(r_.resolve_cycles, false);
  }

  void command(size_t index, const Command& cmd, const EstimateProgress& progress) {
    // `clear_bytes`: bytes a pixel the command writes over the framebuffer (0: no clear).
    const auto state = [&](uint64_t clear_bytes) {
      if (progress) progress(index, 0, r_);
      state_command(cmd, clear_bytes);
    };
    visit_command(cmd, Overloaded{
        [&](const CmdViewport&) { state(0); },
        [&](const CmdScissor&) { state(0); },
        [&](const CmdClear&) { state(4); },
        [&](const CmdClearDepth&) { state(depth_bytes_); },
        [&](const CmdPrimitives& prims) { primitives(index, cmd, prims, progress); },
        [&](const CmdDraw2d& d2) {
          if (progress) progress(index, 0, r_);
          draw2d(cmd, d2);
        },
    });
  }

 private:
  // A state command: fetch's header, the marker down the triangle path, and the ROP's
  // cycles (a clear's over the whole framebuffer), as sc/command_fetch and sc/rop.
  void state_command(const Command& cmd, uint64_t clear_bytes) {
    Framebuffer no_fb;  // clears pass to the ROP; only viewport and scissor matter here
    apply_state_command(cmd, st_, no_fb);
    if (hiz_) hiz_->state(cmd);  // a depth clear resets the table
    work(StageId::CommandFetch, p_.fetch_header_cycles());
    r_.framebuffer_bytes += fb_pixels_ * clear_bytes;
    marker(p_.rop_state_cycles(clear_bytes != 0, fb_pixels_), false);
  }

  // A primitives command's triangles, one transaction each down to setup (a culled one
  // stops there), then traversal's. A clip-space command goes whole to the front end,
  // which charges each triangle out its step (TimingParams::front_end_step_cycles) and
  // ends the command with a transaction of its own, as sc/front_end.
  void primitives(size_t index, const Command& cmd, const CmdPrimitives& prims, const EstimateProgress& progress) {
    const bool clip = prims.clip_space();
    if (clip) {
      if (progress) progress(index, 0, r_);
      work(StageId::CommandFetch, p_.fetch_whole_command_cycles(prims.clip_vertices.size()));
      emit(StageId::CommandFetch);  // the job to the front end and the marker down the command FIFO
    }
    FrontEndStats& fe = r_.render.front_end;
    FrontEndStats last = fe;
    size_t k = 0;
    for_each_triangle(prims, st_, cmd.loc, fe, [&](const ScreenTriangle& v) {
      if (clip) {
        front_end_write(p_.front_end_step_cycles(last, fe, true));
        last = fe;
      } else {
        if (progress) progress(index, k, r_);
        work(StageId::CommandFetch, p_.fetch_triangle_cycles(k == 0, (k == 0 || prims.topology == Topology::List) ? 3 : 1));
      }
      work(StageId::PrimAssembly, p_.assembly_triangle_cycles());
      ++k;
      ++r_.render.triangles_in;
      SetupTriangle tri;
      const SetupOutcome outcome = setup_triangle(v, st_, cmd.loc, tri);
      tri.texture = prims.texture;  // as sc/tri_setup: the texture stage's batches
      stage(StageId::TriSetup).busy += p_.setup_triangle_cycles();
      if (!count_setup_outcome(outcome, r_.render)) return;  // culled: no transaction out
      emit(StageId::TriSetup);
      r_.latency_waits += p_.setup_pipeline_latency();
      traverse(tri);
    });
    if (clip) {
      front_end_write(p_.front_end_step_cycles(last, fe, false));  // the command's end
    } else if (k == 0) {  // no triangle: a header, no transaction
      if (progress) progress(index, 0, r_);
      stage(StageId::CommandFetch).busy += p_.fetch_header_cycles();
    }
  }

  // The front end writes one transaction after `cycles`; its reader waits out the pipeline.
  void front_end_write(uint64_t cycles) {
    work(StageId::FrontEnd, cycles);
    r_.latency_waits += p_.front_end_pipeline_latency();
  }

  // A stage spends `cycles` on one transaction and writes it to the next FIFO.
  void work(StageId s, uint64_t cycles) {
    stage(s).busy += cycles;
    emit(s);
  }
  void emit(StageId s) { ++stage(s).transactions_out; }
  EstimateStage& stage(StageId s) { return r_.stages[stage_index(s)]; }

  // A state command or 2D marker after fetch: one issue slot in each stage from assembly
  // to interpolation (Stage::pass_state), with setup's and interpolation's latencies,
  // then `rop_cycles` in the ROP (which writes a port grant only for a 2D marker).
  void marker(uint64_t rop_cycles, bool is_2d) {
    for (StageId s : {StageId::PrimAssembly, StageId::TriSetup, StageId::CoarseRaster, StageId::FineRaster, StageId::Interpolate}) work(s, TimingParams::state_pass_cycles());
    r_.latency_waits += p_.setup_pipeline_latency() + p_.interp_pipeline_latency();
    stage(StageId::Rop).busy += rop_cycles;
    if (is_2d) emit(StageId::Rop);
  }

  void draw2d(const Command& cmd, const CmdDraw2d& d2) {
    check_2d_sample_count(cmd, st_);
    // Fetch writes the command to the 2D front end and its marker down the triangle path.
    work(StageId::CommandFetch, p_.fetch_draw2d_cycles(draw2d_vertex_count(d2)));
    emit(StageId::CommandFetch);
    const Draw2dWork w = draw2d_ops(d2, cmd.loc, st_);
    ++(w.culled ? r_.render.draw2d.primitives_culled : r_.render.draw2d.primitives);
    work(StageId::Draw2dSetup, p_.setup2d_cycles(w.ops.size()));
    uint64_t engine = TimingParams::engine2d_grant_cycles();
    for (const Op2d& op : w.ops) engine += p_.engine2d_op_cycles(op, w.paint.rop3);
    work(StageId::Engine2d, engine);  // its "done" back to the ROP
    marker(TimingParams::rop_draw2d_marker_cycles(), true);
  }

  // Coarse raster's walk of one set-up triangle by raster.traversal, as sc/coarse_raster.
  void traverse(const SetupTriangle& t) {
    TraversalCounters& c = r_.render.traversal;
    const int F = tp_.frac_bits;
    switch (tp_.method) {
      case Traversal::Tiled: {
        const PixelRect tiles = tile_range(t.bbox, tp_.tile_size);
        TiledWalk walk = p_.tiled_walk();
        for (int ty = tiles.y0; ty < tiles.y1; ++ty) {
          for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
            const PixelRect fp = tile_footprint(t.bbox, tp_.tile_size, tx, ty);
            ++c.tiles_visited;
            const TileClass cls = classify_tile(t, fp, F);
            // Hi-Z as sc/coarse_raster: a culled tile takes its slot and is not sent.
            const bool culled = cls != TileClass::Rejected && hiz_ && hiz_->test(t, fp, cls) == HizDecision::Culled;
            walk.visit(cls != TileClass::Rejected && !culled);
            if (cls == TileClass::Rejected) {
              ++c.tiles_rejected;
              continue;
            }
            ++(cls == TileClass::Accepted ? c.tiles_accepted : c.tiles_partial);
            if (culled) continue;
            if (hiz_) hiz_->apply(t, fp, cls);
            tile(t, fp, cls, false);
          }
        }
        stage(StageId::CoarseRaster).busy += walk.cycles();
        break;
      }
      case Traversal::Bbox:
        ++c.tiles_visited;
        ++c.tiles_partial;
        tile(t, t.bbox, TileClass::Partial, false);
        stage(StageId::CoarseRaster).busy += p_.coarse_walk_cycles(1);
        break;
      case Traversal::Hierarchical: {
        const uint64_t visited0 = c.tiles_visited;
        walk_hierarchical(t, t.bbox, tp_.hier_levels, 0, F, c,
                          [&](const PixelRect& fp, TileClass cls) { tile(t, fp, cls, false); });
        stage(StageId::CoarseRaster).busy += p_.coarse_walk_cycles(c.tiles_visited - visited0);
        break;
      }
      case Traversal::Scanline: {
        uint64_t rows = 0;
        scanline_spans(t, tp_.scan_arith, F, [&](int py, int x0, int x1) {
          ++rows;
          if (x0 >= x1) return;
          ++c.spans;
          tile(t, PixelRect{x0, py, x1, py + 1}, TileClass::Accepted, true);
        });
        stage(StageId::CoarseRaster).busy += p_.scanline_walk_cycles(rows);
        break;
      }
    }
  }

  // One tile item through fine raster, interpolation and the ROP, as sc/fine_raster.
  // Per covered pixel of mask m (S = raster.samples): interpolation shades 1 fragment
  // (S = 1, msaa) or popcount(m) (ssaa), and the ROP makes rop_accesses(m, S) accesses
  // (msaa) or one per shaded fragment (ssaa: one sample each), as sc/interpolate, sc/rop.
  void tile(const SetupTriangle& t, const PixelRect& fp, TileClass cls, bool span) {
    emit(StageId::CoarseRaster);
    TraversalCounters& c = r_.render.traversal;
    const int S = t.samples;
    const bool ssaa = S > 1 && t.aa_mode == AaMode::Ssaa;
    uint64_t n = 0, cost = 0;     // covered pixels; fine raster cycles
    uint64_t shaded = 0, acc = 0;  // fragments out of interpolation; ROP accesses
    // `count` pixels of mask m (an accepted footprint's are all one mask: O(1), not O(area)).
    auto pixel = [&](uint32_t m, uint64_t count = 1) {
      n += count;
      const uint64_t k = ssaa ? uint64_t(std::popcount(m)) : 1;
      shaded += k * count;
      acc += (ssaa ? k : TimingParams::rop_accesses(m, S)) * count;
    };
    if (span) {
      pixel(1u, uint64_t(fp.area()));
      c.count_accepted(fp.area(), 1);
      cost = p_.fine_span_cycles(n);
    } else if (cls == TileClass::Accepted) {
      pixel(t.full_mask(), uint64_t(fp.area()));
      c.count_accepted(fp.area(), S);
      cost = p_.fine_accepted_cycles();
    } else {
      const uint64_t tests = fine_raster_partial(t, fp, tp_.frac_bits, [&](int, int, uint32_t m) {
        c.count_pixel(m, S);
        pixel(m);
      });
      c.count_tests(tests, S);
      cost = p_.fine_partial_cycles(tests, S);
    }
    r_.render.fragments_shaded += shaded;
    r_.rop_accesses += acc;
    r_.framebuffer_bytes += acc * (4 + depth_bytes_);
    stage(StageId::FineRaster).busy += cost;
    if (n == 0) return;  // an empty tile leaves nothing
    emit(StageId::FineRaster);
    // Early Z: the fragments a batch keeps are not known here; early_bounds() charges
    // interpolation and texturing from the reference's totals instead.
    if (st_.depth_early) emit(StageId::Interpolate);
    else work(StageId::Interpolate, p_.interp_batch_cycles(shaded, t.affine));
    r_.latency_waits += p_.interp_pipeline_latency();
    stage(StageId::Rop).busy += p_.rop_fragment_cycles(acc);  // culled early: still its depth reads
    if (t.texture.enabled()) {
      if (st_.depth_early) {
        textured_ = true;
        emit(StageId::Texture);
      } else {
        texture_batch(t.texture.filter, shaded);
      }
    }
  }

 public:
  // depth.early: the interpolation and texture busy cycles of the fragments the early
  // test kept (`ref`: the reference's counts of the scene), bounded from below by their
  // totals (docs/estimate.md): sum over batches of ceil(n_b / lanes) >= ceil(sum n_b /
  // lanes) with the affine (widest) lanes; the texture stage's fragments term alone.
  void early_bounds(const RenderStats& ref) {
    if (!st_.depth_early) return;
    stage(StageId::Interpolate).busy += p_.interp_batch_cycles(ref.fragments_shaded, true);
    if (ref.texture.total_samples() == 0) return;
    TimingParams::TextureWork w;
    w.fragments = ref.texture.total_samples();
    stage(StageId::Texture).busy += p_.texture_batch_cycles(w);
  }

 private:

  // A textured batch of `fragments` through the texture stage (sc/texture): the terms of
  // TimingParams::texture_batch_cycles the counts give, its fewest sample slots, texel
  // fetches (1 a nearest sample, 4 a bilinear or trilinear one: one level read at least)
  // and its fragments; its quads and cache misses need the texture unit itself and count
  // 0 here, so this stays at most the simulated busy (a lower bound; no upper bound).
  void texture_batch(TexFilter filter, uint64_t fragments) {
    textured_ = true;
    TimingParams::TextureWork w;
    w.bilinear_slots = fragments;  // one level sample a fragment at least (trilinear: 2 where it blends two)
    w.texel_fetches = fragments * (filter == TexFilter::Nearest ? 1 : 4);
    w.fragments = fragments;
    work(StageId::Texture, p_.texture_batch_cycles(w));
  }

 public:
  // A texture stage batch was counted (its busy cycles are only a lower bound).
  bool textured() const { return textured_; }

 private:
  bool textured_ = false;
  std::optional<HizTracker> hiz_;  // depth.hiz where it applies: the timed coarse raster's culls

  RasterState st_;
  TraversalParams tp_;
  const TimingParams& p_;
  EstimateResult& r_;
  uint64_t fb_pixels_, depth_bytes_;
};

// With memory.model = "dram" (docs/estimate.md, "Bandwidth bound"): the reference's DRAM
// bytes and the bounds they give. Every byte the ROP's line fills read crosses a DRAM
// data bus before the transaction that waits for it ends (the multisample resolve's fills
// too), so cycles >= bytes read / peak; posted writes may still be queued at the end, so
// written bytes bound only the DRAM's last completion. The DRAM moves whole bursts, at
// least the bytes counted. Floors, so rounding never lifts a bound above the truth.
void bandwidth_bounds(const RenderStats& rs, const ArchParams& a, EstimateResult& r) {
  if (!a.memory.enabled) return;
  const MemoryStats& m = rs.memory;
  r.dram_bytes_read = m.rop_color.bytes_read + m.rop_depth.bytes_read;
  r.dram_bytes_written = m.rop_color.bytes_written + m.rop_depth.bytes_written;
  r.dram_peak_bytes_per_cycle = a.dram.peak_bytes_per_second() / (double(a.dram.core_khz) * 1e3);
  const auto cycles_for = [&](uint64_t bytes) {
    return uint64_t(std::floor(double(bytes) / r.dram_peak_bytes_per_cycle));
  };
  r.bandwidth_lower_bound = cycles_for(r.dram_bytes_read);
  r.dram_lower_bound = cycles_for(r.dram_bytes_read + r.dram_bytes_written);
}

}  // namespace

EstimateResult estimate_scene(const Scene& scene, const ArchParams& params, const EstimateProgress& progress,
                              const RenderStats* reference) {
  const auto t0 = std::chrono::steady_clock::now();
  const RasterState& arch = params.raster;
  const TimingParams& p = params.timing;
  EstimateResult r;
  r.core_mhz = p.core_mhz;
  Walker walker(arch, p, r);
  for (size_t i = 0; i < scene.commands.size(); ++i) walker.command(i, scene.commands[i], progress);
  walker.end_of_frame();
  // The reference's counts, where a bound needs them: the DRAM bytes, early Z's kept fragments.
  RenderStats own;
  if (!reference && (params.memory.enabled || arch.depth_early))
    render_scene(scene, arch, own, {}, Framebuffer::kDefaultTileLog2, 1, params.memory);
  const RenderStats& ref = reference ? *reference : own;
  walker.early_bounds(ref);

  // Lower bound: a stage with work cannot start before its fill and is busy for all its
  // cycles (docs/estimate.md). Upper bound: until the simulation ends some stage is
  // always in a timed wait (busy, or a reader waiting out a transaction's pipeline
  // latency); otherwise SystemC would have no event left and stop.
  uint64_t busy_sum = 0;
  for (size_t s = 0; s < r.stages.size(); ++s) {
    busy_sum += r.stages[s].busy;
    if (r.stages[s].busy > 0)
      r.stage_lower_bound = std::max(r.stage_lower_bound, p.stage_fill_cycles(kStages[s].id) + r.stages[s].busy);
  }
  bandwidth_bounds(ref, params, r);
  r.cycles_lower_bound = std::max(r.stage_lower_bound, r.bandwidth_lower_bound);
  // The ROP's busy cycles under DRAM include its fills' waits, which no count bounds; the
  // texture stage's include its cache misses, which only the texture unit counts; early
  // Z's interpolation is charged a lower bound, not each batch's cycles.
  r.cycles_upper_bound = params.memory.enabled || walker.textured() || arch.depth_early
                             ? EstimateResult::kNoUpperBound
                             : busy_sum + r.latency_waits;
  r.cycles_estimate = r.cycles_lower_bound;
  if (r.has_upper_bound())
    r.cycles_estimate +=
        uint64_t(std::llround(kEstimateBlend * double(r.cycles_upper_bound - r.cycles_lower_bound)));
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

nlohmann::json EstimateResult::to_json() const {
  nlohmann::json j;
  j["cycles_lower_bound"] = cycles_lower_bound;
  j["stage_lower_bound"] = stage_lower_bound;
  j["bandwidth_lower_bound"] = bandwidth_lower_bound;
  j["cycles_upper_bound"] = has_upper_bound() ? nlohmann::json(cycles_upper_bound) : nlohmann::json(nullptr);
  if (dram_peak_bytes_per_cycle > 0) {
    j["dram_bytes_read"] = dram_bytes_read;
    j["dram_bytes_written"] = dram_bytes_written;
    j["dram_peak_bytes_per_cycle"] = dram_peak_bytes_per_cycle;
    j["dram_lower_bound"] = dram_lower_bound;
  }
  j["cycles_estimate"] = cycles_estimate;
  j["latency_wait_cycles"] = latency_waits;
  j["core_mhz"] = core_mhz;
  j["estimated_seconds"] = double(cycles_estimate) / (core_mhz * 1e6);
  j["wall_seconds"] = wall_seconds;
  j["rop_accesses"] = rop_accesses;
  j["framebuffer_bytes"] = framebuffer_bytes;
  j["resolve_cycles"] = resolve_cycles;
  for (size_t s = 0; s < stages.size(); ++s)
    j["stages"][std::string(kStages[s].name)] = {{"busy", stages[s].busy}, {"transactions_out", stages[s].transactions_out}};
  // The geometry counters the walk produces (the same values as render/simulate); the
  // ones it does not compute (depth test, image, interpolation error, 2D pixels) are left out.
  const nlohmann::json all = rastsim::to_json(render);
  for (const char* key : {"triangles_in", "triangles_culled", "triangles_zero_area", "triangles_facing_culled",
                          "triangles_out_of_range", "triangles_outside_clip", "triangles_rasterized", "tiles_visited",
                          "tiles_rejected", "tiles_accepted", "tiles_partial", "pixel_tests", "fragments",
                          "samples", "aa_mode", "sample_tests", "samples_covered", "pixels_partially_covered",
                          "fragments_shaded", "color_buffer_bytes", "depth_buffer_bytes", "resolve_bytes",
                          "primitives_2d", "primitives_2d_culled", "traversal", "spans", "clip_triangles_in",
                          "triangles_behind", "triangles_culled_outside", "triangles_clipped", "clip_vertices_made",
                          "triangles_nonfinite", "clip_triangles_out", "points_in", "points_culled", "lines_in",
                          "lines_culled", "lines_clipped"})
    if (all.contains(key)) j[key] = all[key];
  return j;
}

}  // namespace rastsim
