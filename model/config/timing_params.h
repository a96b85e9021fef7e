// SPDX-License-Identifier: Apache-2.0
// TimingParams: the config's timing keys (config_schema_timing.cpp), read and checked
// once; no defaults of its own. The SystemC model (model/sc) times its stages with them
// and the RTL parameter export (rtl_params.cpp) builds the Verilog with the same values.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "config/config.h"
#include "ref/2d/draw2d.h"
#include "ref/front_end.h"
#include "ref/sample_pattern.h"
#include "timing/stage_table.h"
#include "timing/tiled_walk.h"

namespace rastsim {

// ceil(n / per_cycle), the cost of n items through a port of per_cycle items a cycle.
inline uint64_t ceil_div(uint64_t n, uint64_t per_cycle) { return (n + per_cycle - 1) / per_cycle; }

struct TimingParams {
  double core_mhz = 0;
  uint64_t fetch_cycles_per_command = 0, fetch_vertices_per_cycle = 0;
  uint64_t front_end_cycles_per_primitive = 0, front_end_clip_cycles_per_vertex = 0;
  uint64_t front_end_vertices_per_cycle = 0, front_end_latency = 0;
  uint64_t assembly_cycles_per_triangle = 0;
  uint64_t setup_interval = 0, setup_latency = 0;
  uint64_t coarse_tiles_per_cycle = 0;
  uint64_t fine_samples_per_cycle = 0, fine_accepted_tile_cycles = 0;
  uint64_t coarse_scanline_setup = 0, fine_span_setup = 0, fine_span_pixels_per_cycle = 0;
  uint64_t interp_fragments_per_cycle = 0, interp_latency = 0;
  // The reciprocal unit of perspective-correct interpolation (docs/clip-space.md, "Timing"):
  // present when interp.perspective is true; interp.recip_iterations steps; recip.lanes.
  bool interp_perspective = false;
  uint64_t recip_iterations = 0, recip_lanes = 0;
  uint64_t rop_pixels_per_cycle = 0, rop_clear_pixels_per_cycle = 0, rop_resolve_bytes_per_cycle = 0;
  uint64_t setup2d_ops_per_cycle = 0;
  uint64_t engine2d_fill_pixels_per_cycle = 0, engine2d_span_setup = 0, engine2d_rmw = 0;
  uint64_t engine2d_blit_bytes_per_cycle = 0;
  int fifo_draw2d = 0, fifo_op2d = 0;
  int fifo_clip_command = 0, fifo_screen = 0;
  int fifo_command = 0, fifo_triangle = 0, fifo_setup = 0, fifo_tile = 0, fifo_pixel = 0, fifo_fragment = 0;
  // The texture stage (docs/texture.md, "Timed texture stage"): quads through level of
  // detail and addressing, bilinear samples filtered, texels through the cache port and
  // fragments combined a cycle, and the cycles a texture-cache line miss stalls it.
  uint64_t texture_quads_per_cycle = 0, texture_bilinear_per_cycle = 0, texture_texels_per_cycle = 0;
  uint64_t texture_combine_per_cycle = 0, texture_miss_cycles = 0;
  uint64_t texture_latency = 0;  // texture.latency_cycles: a shaded batch reaches the ROP this much after its end
  int fifo_texture = 0;

  // Entries of the FIFO after a stage with a pipeline latency: the configured depth plus
  // the transactions in flight inside the stage's pipeline (its pipeline registers),
  // so that latency costs time but not throughput.
  int setup_fifo_entries() const { return fifo_setup + int(ceil_div(setup_latency - setup_interval, setup_interval)); }
  int fragment_fifo_entries() const { return fifo_fragment + int(interp_pipeline_latency()); }
  int texture_fifo_entries() const { return fifo_texture + int(interp_pipeline_latency()); }
  int screen_fifo_entries() const { return fifo_screen + int(front_end_latency); }

  // The interpolator's reciprocal unit (rtl/rast_recip.sv inside rtl/rast_interpolate.sv)
  // sits in its pipeline whenever interp.perspective is true, for every triangle (a static
  // pipeline: an affine triangle's fragments wait as long): the seed look-up (1 stage), 2
  // stages a Newton-Raphson step, and 1 stage for the product n' y. 0 without the unit.
  uint64_t interp_recip_latency() const { return interp_perspective ? 2 + 2 * recip_iterations : 0; }
  // Cycles from a fragment's pick to its leaving the interpolator beyond its issue cycle:
  // the divider pipeline (interp.latency_cycles) plus the reciprocal unit's.
  uint64_t interp_pipeline_latency() const { return interp_latency + interp_recip_latency(); }
  // Pixels interpolated a cycle: interp.fragments_per_cycle, and for a triangle that
  // needs the reciprocal (not affine) no more than the unit's recip.lanes.
  uint64_t interp_lanes(bool affine) const {
    return affine || !interp_perspective ? interp_fragments_per_cycle : std::min(interp_fragments_per_cycle, recip_lanes);
  }

  // The stages' cost equations (docs/microarchitecture.md), in cycles. The SystemC
  // stages and the RTL testbench's stages (model/rtlsim) both call these.
  // Command fetch: the command header (paid once a command, with its first triangle)
  // plus its new vertices; a list triangle brings 3, a strip or fan triangle after the
  // first brings 1.
  uint64_t fetch_triangle_cycles(bool first_of_command, uint64_t new_vertices) const {
    return (first_of_command ? fetch_cycles_per_command : 0) + ceil_div(new_vertices, fetch_vertices_per_cycle);
  }
  // Command fetch of a command handed on whole (a 2D command to the 2D front end, a
  // clip-space command to the geometry front end): the header plus its vertices.
  uint64_t fetch_whole_command_cycles(uint64_t vertices) const {
    return fetch_cycles_per_command + ceil_div(vertices, fetch_vertices_per_cycle);
  }
  uint64_t fetch_draw2d_cycles(uint64_t vertices) const { return fetch_whole_command_cycles(vertices); }
  // Command fetch of a state command (viewport, scissor, clear) or of a primitives
  // command with no triangle: its header alone.
  uint64_t fetch_header_cycles() const { return fetch_cycles_per_command; }
  // Any stage's issue slot for a state command or 2D marker it passes on (Stage::pass_state).
  static constexpr uint64_t state_pass_cycles() { return 1; }
  // The geometry front end (docs/clip-space.md, "Levels"). A clip-space primitive
  // (triangle, point or line segment, culled ones too) takes front_end.cycles_per_primitive
  // for its plane tests and cull decision, plus front_end.clip_cycles_per_vertex for each
  // vertex clipping makes (the division for t and the interpolation of its attributes).
  uint64_t front_end_primitive_cycles(uint64_t primitives, uint64_t clip_vertices_made) const {
    return primitives * front_end_cycles_per_primitive + clip_vertices_made * front_end_clip_cycles_per_vertex;
  }
  // Each screen-space triangle out takes its new vertices through the divide and viewport
  // lanes (front_end.vertices_per_cycle): 3 for the first triangle of a primitive, 1 for
  // each later one (a clipped polygon is fanned; a point's or line's quad has 4 corners).
  uint64_t front_end_triangle_cycles(bool first_of_primitive) const {
    return ceil_div(first_of_primitive ? 3 : 1, front_end_vertices_per_cycle);
  }
  // The primitives the front end has taken in, by its counters.
  static uint64_t front_end_primitives(const FrontEndStats& s) { return s.clip_triangles_in + s.points_in + s.lines_in; }
  // The front end's cycles between two points of its run over a command, by its counters
  // at each (`from`, `to`): the primitives taken in since and the vertices clipping made,
  // then, when `to` is at a triangle out (`triangle_out`), that triangle's vertices (the
  // first of its primitive when a primitive was taken in since). A command's cycles are
  // these steps from its start to each triangle out, then to its end.
  uint64_t front_end_step_cycles(const FrontEndStats& from, const FrontEndStats& to, bool triangle_out) const {
    const uint64_t taken = front_end_primitives(to) - front_end_primitives(from);
    return front_end_primitive_cycles(taken, to.clip_vertices_made - from.clip_vertices_made) +
           (triangle_out ? front_end_triangle_cycles(taken > 0) : 0);
  }
  // Cycles a triangle leaving the front end waits beyond its issue (the divide and
  // viewport pipeline: front_end.latency_cycles).
  uint64_t front_end_pipeline_latency() const { return front_end_latency; }
  // Primitive assembly of one triangle; triangle setup's issue slot for one triangle
  // (its initiation interval; the rest of setup.latency_cycles is pipeline latency).
  uint64_t assembly_triangle_cycles() const { return assembly_cycles_per_triangle; }
  uint64_t setup_triangle_cycles() const { return setup_interval; }
  // Cycles a transaction leaving setup waits beyond setup's issue slot (its pipeline).
  uint64_t setup_pipeline_latency() const { return setup_latency - setup_interval; }
  // Fine raster of an accepted footprint (a full mask, no tests), any size.
  uint64_t fine_accepted_cycles() const { return fine_accepted_tile_cycles; }
  // Interpolation of a batch of n fragments (one tile's or span's), excluding its latency.
  // A perspective-correct (non-affine) triangle's batch at interp_lanes(false) a cycle.
  uint64_t interp_batch_cycles(uint64_t fragments, bool affine = true) const {
    return ceil_div(fragments, interp_lanes(affine));
  }
  // ROP: a batch of fragments; a clear (colour or depth) of the whole framebuffer at the
  // fast-clear rate; any other state command passes in one cycle.
  // With raster.samples = S > 1 the ROP's unit of work is an access, not a fragment
  // (docs/antialiasing.md): a fragment whose mask is full writes its pixel once (all
  // samples one value: the compression rule), any other fragment one access per covered
  // sample. rop.pixels_per_cycle accesses a cycle. A one-sample fragment is 1 access.
  static uint64_t rop_accesses(uint32_t mask, int samples) {
    return (samples == 1 || mask == full_sample_mask(samples)) ? 1 : uint64_t(std::popcount(mask));
  }
  uint64_t rop_fragment_cycles(uint64_t accesses) const { return ceil_div(accesses, rop_pixels_per_cycle); }
  // The frame-end resolve pass of a W x H framebuffer of S samples: W H S 4 bytes read and
  // W H 4 written at rop.resolve_bytes_per_cycle; 0 cycles for S = 1 (no pass). A clear of
  // a multisampled buffer costs what a one-sample clear does (rop_clear_cycles of W x H:
  // every pixel's samples get one value, written compressed once).
  uint64_t resolve_cycles(uint64_t fb_pixels, int samples) const {
    if (samples == 1) return 0;
    return ceil_div(fb_pixels * uint64_t(samples) * 4 + fb_pixels * 4, rop_resolve_bytes_per_cycle);
  }
  uint64_t rop_clear_cycles(uint64_t pixels) const { return ceil_div(pixels, rop_clear_pixels_per_cycle); }
  // ROP of a state command: a clear of the fb_pixels framebuffer, or 1 cycle.
  uint64_t rop_state_cycles(bool is_clear, uint64_t fb_pixels) const {
    return is_clear ? rop_clear_cycles(fb_pixels) : state_pass_cycles();
  }
  // ROP on a 2D command's marker: 1 cycle after the 2D engine hands its port back.
  static constexpr uint64_t rop_draw2d_marker_cycles() { return 1; }

  // The texture stage on one batch of textured fragments (docs/texture.md, "Timed texture
  // stage"): its four units run in a pipeline, so the slowest sets the batch's cycles,
  // and each texture-cache line miss stalls the whole pipeline texture.miss_cycles:
  //   max(ceil(Q / quads_per_cycle), ceil(B / bilinear_per_cycle),
  //       ceil(T / texels_per_cycle), ceil(N / combine_per_cycle), B) + S + M miss_cycles
  // Q the batch's 2x2 quads (helper pixels ride in their quad's lanes), B its level
  // samples (TextureStats::level_samples: a nearest or bilinear sample 1, a trilinear
  // sample 2 where it blends two levels, half rate, and 1 where its weight is 0), T its
  // texel fetches, N its fragments, M its line misses. At least 1 cycle a batch. The
  // term B alone: the texel fetch port takes one level sample (1 or 4 texels) a cycle
  // (rast_top's one tex_req port, the texture cache's interface), whatever the lanes
  // behind it. S, the lookup groups a miss splits (rtl/rast_texture_cache.sv looks a
  // missing texel up as the first of a cycle: one more cycle where hits of its request
  // share its group; texture_cache_ports), adds S cycles with either memory.
  struct TextureWork {
    uint64_t quads = 0, bilinear_slots = 0, texel_fetches = 0, fragments = 0, misses = 0, miss_splits = 0;
  };
  // Texels the texture cache looks up a cycle (rast_texture_cache's Ports): the stage's
  // texel port shared by its bilinear_per_cycle lanes, at most a request's 4 texels.
  uint64_t texture_cache_ports() const {
    return std::clamp<uint64_t>(ceil_div(texture_texels_per_cycle, texture_bilinear_per_cycle), 1, 4);
  }
  uint64_t texture_batch_cycles(const TextureWork& w) const {
    const uint64_t rate = std::max({ceil_div(w.quads, texture_quads_per_cycle),
                                    ceil_div(w.bilinear_slots, texture_bilinear_per_cycle),
                                    ceil_div(w.texel_fetches, texture_texels_per_cycle),
                                    ceil_div(w.fragments, texture_combine_per_cycle), w.bilinear_slots,
                                    uint64_t{1}});
    return rate + w.miss_splits + w.misses * texture_miss_cycles;
  }

  // Traversal (docs/traversal.md). Coarse raster classifies coarse_tiles_per_cycle tiles a
  // cycle at every level: tile i of a walk (counted from 0 over all levels, in walk order)
  // leaves at cycle i / tiles_per_cycle + 1; a walk of V tiles takes max(1, ceil(V / this)).
  uint64_t coarse_walk_cycles(uint64_t tiles) const { return std::max<uint64_t>(1, ceil_div(tiles, coarse_tiles_per_cycle)); }
  // The tiled walk's cycle model (timing/tiled_walk.h), at coarse.tiles_per_cycle.
  TiledWalk tiled_walk() const { return TiledWalk{coarse_tiles_per_cycle}; }
  // Fine raster: a partial footprint (a tile, or the whole bbox for raster.traversal =
  // bbox) of A pixels, i.e. A x raster.samples coverage tests, at fine.samples_per_cycle.
  uint64_t fine_partial_cycles(uint64_t pixels, int samples = 1) const {
    return ceil_div(pixels * uint64_t(samples), fine_samples_per_cycle);
  }
  // Scanline: the edge walker's setup, then one row a cycle (rows inside the bbox, empty
  // spans included); the span filler's setup plus the span's n pixels.
  uint64_t scanline_walk_cycles(uint64_t rows) const { return coarse_scanline_setup + rows; }
  uint64_t fine_span_cycles(uint64_t n) const { return fine_span_setup + ceil_div(n, fine_span_pixels_per_cycle); }

  // The 2D path (docs/2d.md, "Timing").
  // Front end: one command's N engine operations.
  uint64_t setup2d_cycles(uint64_t ops) const { return std::max<uint64_t>(1, ceil_div(ops, setup2d_ops_per_cycle)); }
  // Engine, one beat: 1 cycle, or rmw when the ROP3 code reads D (read, wait, write).
  uint64_t engine2d_beat_cycles(bool reads_d) const { return reads_d ? engine2d_rmw : 1; }
  // A span of n pixels (clipped, n >= 1): set-up, then beats of fill_pixels_per_cycle.
  uint64_t engine2d_span_cycles(uint64_t n, bool reads_d) const {
    return engine2d_span_setup + ceil_div(n, engine2d_fill_pixels_per_cycle) * engine2d_beat_cycles(reads_d);
  }
  // One pixel of a pixel stream (diamond and DDA lines, outlines): one beat.
  uint64_t engine2d_pixel_cycles(bool reads_d) const { return engine2d_beat_cycles(reads_d); }
  // An index-method line of n pixels through the line unit: 1 set-up cycle, then one
  // beat a pixel (clipped pixels walked too).
  uint64_t engine2d_line_cycles(uint64_t n, bool reads_d) const { return 1 + n * engine2d_beat_cycles(reads_d); }
  // A clipped blit of h rows of w pixels: per row set-up, then the row's bytes at the
  // blit bandwidth (4 written, 4 read for each of S and D the code reads), and at most
  // one pixel a cycle (the blitter has one lane: a code that reads no S, e.g. 00 or F0,
  // moves 4 or 8 bytes a pixel, which a bandwidth of 8 would otherwise outrun).
  uint64_t engine2d_blit_cycles(uint64_t w, uint64_t h, bool reads_s, bool reads_d) const {
    const uint64_t bytes = 4 + (reads_s ? 4 : 0) + (reads_d ? 4 : 0);
    return h * (engine2d_span_setup + std::max(w, ceil_div(w * bytes, engine2d_blit_bytes_per_cycle)));
  }
  // Engine: taking the ROP's framebuffer port at the start of each 2D command.
  static constexpr uint64_t engine2d_grant_cycles() { return 1; }
  // Any engine operation of a command painted with ROP3 code `rop3`.
  uint64_t engine2d_op_cycles(const Op2d& op, uint8_t rop3) const;

  // What passing one stage costs the transaction behind it (timing/stage_table.h,
  // StagePass), in cycles: fetch's header, or one issue cycle plus the stage's pipeline
  // latency (setup, interpolation), which every transaction (state markers too) waits.
  uint64_t stage_pass_cycles(StagePass pass) const;
  // The earliest cycle stage `stage` can start its first busy cycle: the pass cycles of
  // every stage upstream of it in fill order (StageInfo::fed_by).
  uint64_t stage_fill_cycles(StageId stage) const;
  // Entries of a link (timing/stage_table.h): the configured depth, plus the pipeline
  // slots of setup and interpolation behind theirs; a port handshake holds one.
  int fifo_entries(FifoId fifo) const;

  // Reads and cross-checks the keys (setup.latency_cycles >= setup.interval_cycles);
  // throws ConfigError naming the keys.
  static TimingParams from_config(const Config& cfg);
};

}  // namespace rastsim

namespace rastsim::sc {
using rastsim::ceil_div;
using rastsim::TimingParams;
}  // namespace rastsim::sc
