// SPDX-License-Identifier: Apache-2.0
// The reference pipeline: command stream -> primitive assembly -> setup -> traversal
// -> interpolation -> ROP, untimed. This is the golden model every other level is
// compared with (framebuffer CRC and fragment stream).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "ref/2d/draw2d.h"
#include "ref/binning.h"
#include "ref/framebuffer.h"
#include "ref/hiz.h"
#include "ref/front_end.h"
#include "ref/interpolate.h"
#include "ref/memory/rop_memory.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "ref/texture/texture_unit.h"
#include "ref/coarse_raster.h"
#include "ref/study/coverage_check.h"

namespace rastsim {

struct RenderStats {
  FrontEndStats front_end;            // the geometry front end (clip-space commands only)
  uint64_t triangles_in = 0;          // triangles out of primitive assembly
  uint64_t triangles_culled = 0;      // zero-area + facing culls
  uint64_t triangles_zero_area = 0;
  uint64_t triangles_facing_culled = 0;
  uint64_t triangles_out_of_range = 0;  // raster.out_of_range = cull
  uint64_t triangles_outside_clip = 0;  // no pixel centre inside viewport/scissor box
  uint64_t triangles_rasterized = 0;    // reached the tile walker
  TraversalCounters traversal;
  Traversal traversal_method = Traversal::Tiled;  // raster.traversal, for the stats
  CoverageErrors coverage;            // inexact traversal against the exact rule
  uint64_t fragments_passed = 0;        // passed the depth test and were written
  uint64_t depth_writes = 0;            // depth values the ROP wrote, one a sample
  // Early depth test (depth.early, docs/depth.md): fragments it culled, and the work they
  // did not do: attribute values not interpolated (3 colour channels a fragment, 2 texture
  // coordinates more when textured) and texture samples not taken.
  bool depth_early = false;
  uint64_t fragments_culled_early = 0;
  uint64_t interpolations_saved = 0;
  uint64_t texture_samples_saved = 0;
  // Hierarchical Z (depth.hiz, ref/hiz.h, docs/depth-culling.md): the mode configured
  // (its stats keys appear when not off) and the unit's counts (hiz.enabled: the run could
  // use it: single sample, tiled traversal, plane interpolation, a depth function it handles).
  HizMode hiz_mode = HizMode::Off;
  HizStats hiz;
  // interp.method = dda only: |dda - plane| of each fragment's attributes, in LSBs of the
  // attribute (colour channels: 8-bit LSBs; depth: raster.depth_bits LSBs). 0 for plane.
  uint32_t max_attr_error_lsb = 0, max_depth_error_lsb = 0;
  uint64_t attr_error_sum = 0, depth_error_sum = 0;  // sums, for the means (3 colour samples a fragment)
  Draw2dStats draw2d;                   // 2D primitives (points, lines, circles, fills, blits)
  // Multisampling (raster.samples = S, docs/antialiasing.md).
  int samples = 1;
  AaMode aa_mode = AaMode::Msaa;
  uint64_t samples_passed = 0;          // samples written by the ROP
  uint64_t fragments_shaded = 0;        // fragments out of interpolation (ssaa: one a covered sample)
  uint64_t color_buffer_bytes = 0;      // W x H x S x 4 (RGBA8)
  uint64_t depth_buffer_bytes = 0;      // W x H x S x ceil(raster.depth_bits / 8)
  uint64_t resolve_bytes = 0;           // the resolve pass: W H S 4 read + W H 4 written; 0 for S = 1
  uint32_t framebuffer_crc32 = 0;
  double wall_seconds = 0;
  // The functional memory system's counts (memory.model != fixed; docs/memory.md).
  MemoryStats memory;
  // The texture unit's counts (docs/texture.md); all 0 when no texture was bound.
  TextureStats texture;
  // The binned pipeline's counts (pipeline.mode = binned; docs/binning.md).
  BinStats bin;
};

// Early Z's saving a culled fragment (RenderStats::interpolations_saved): the attribute
// values it is not interpolated, r, g, b, and s, t when its triangle is textured. The
// reference and the timed model count with this one rule.
inline uint64_t early_interpolations_saved(bool textured) { return textured ? 5 : 3; }

// Of the fragments that fail the late depth test, the fraction early Z and Hi-Z removed
// before fine raster or interpolation (stats key hiz_oracle_fraction,
// docs/depth-culling.md): the culled ones over the culled ones plus those the ROP tested
// and wrote nothing of (fragments_shaded - fragments_passed); 1 when none fails.
// In the reference early Z tests in order against the same depth buffer as the ROP, so
// with depth.early every late failure is removed and the score is 1: hiz_culled_fraction
// is Hi-Z's share alone, fragments_culled_hiz over the same failures.
double hiz_oracle_fraction(const RenderStats& s);
double hiz_culled_fraction(const RenderStats& s);

// Applies a scene's state command (viewport, scissor, clears) to the state and
// framebuffer; returns false for a primitives command (not state). Throws SceneError
// naming the command's file:line for a viewport that does not fit. `mem`, if given,
// sees the clears (RopMemory::clear_color, clear_depth).
bool apply_state_command(const Command& cmd, RasterState& st, Framebuffer& fb, RopMemory* mem = nullptr);
// A depth clear's value in raster.depth_bits' unsigned normalised code (the immediate
// ROP's, the binned pipeline's and the timed binner's); SceneError at `loc` outside [0, 1].
uint32_t clear_depth_value(const CmdClearDepth& c, const SourceLoc& loc, const RasterState& st);

// The state commands' handlers of a walk that treats them alike (visit_command,
// ref/scene.h): each of viewport, clear, clear depth and scissor returns state(). Named
// one a type here, so a walk written
//   visit_command(cmd, Overloaded{state_commands(state), [&](const CmdPrimitives& p) {...},
//                                 [&](const CmdDraw2d& d) {...}});
// still stops the build when a command type is added and not handled.
template <class F>
auto state_commands(F state) {
  return Overloaded{
      [state](const CmdViewport&) { return state(); },
      [state](const CmdClear&) { return state(); },
      [state](const CmdClearDepth&) { return state(); },
      [state](const CmdScissor&) { return state(); },
  };
}

// Counts one triangle-setup outcome in the triangle stats (shared with the timed model);
// returns true when the triangle goes on to traversal.
bool count_setup_outcome(SetupOutcome o, RenderStats& stats);

// Sets the multisample figures of the stats that follow from the state alone (sample
// count, mode, buffer sizes, resolve traffic); shared with the timed model.
void count_multisample_footprint(const RasterState& st, RenderStats& stats);

// Throws SceneError naming `cmd` when it is a 2D drawing command and raster.samples > 1:
// the 2D engine writes pixels, not samples (docs/antialiasing.md).
void check_2d_sample_count(const Command& cmd, const RasterState& st);

// Throws SceneError naming the first 2D drawing command of `scene` for the levels that
// have no 2D stage yet (`level`: "SystemC", "RTL").
void reject_2d_commands(const Scene& scene, const char* level);

// Adds one fragment's attribute error (a method's fragment against interpolate_plane's)
// to the interpolation error stats (shared with the timed model).
void count_interp_error(const Fragment& got, const Fragment& exact, RenderStats& stats);

using FragmentSink = std::function<void(const Fragment&)>;

// One Hi-Z decision other than Draw, as coarse raster makes it: the tile footprint of
// tri, and the framebuffer as the fragments before it left it (the tests' brute-force
// check of conservativeness, tb/test_depth_hiz.cpp).
struct HizEvent {
  const SetupTriangle& tri;
  PixelRect footprint;
  HizDecision decision;
  const Framebuffer& fb;
  DepthFunc func;
};
using HizObserver = std::function<void(const HizEvent&)>;

// Renders a whole scene into a new framebuffer of the display size.
// `on_fragment`, if set, sees every fragment leaving interpolation, in pipeline order.
// `fb_tile_log2`: the framebuffer's storage tiles (Framebuffer; no effect on the result).
// `threads`: see SceneRenderer (no effect on the result). `memory`: the functional memory
// system (stats.memory; no effect on the result).
Framebuffer render_scene(const Scene& scene, const RasterState& arch, RenderStats& stats,
                         const FragmentSink& on_fragment = {}, int fb_tile_log2 = Framebuffer::kDefaultTileLog2,
                         int threads = 1, const MemoryParams& memory = {});

// The same pipeline fed a batch of commands at a time (a scene streamed in batches,
// scene_io.h stream_scene): run() each batch in order, then finish() (coverage check,
// resolve, CRC) once. stats.wall_seconds is the time spent in the constructor, run and
// finish: the pipeline's, parsing excluded, as render_scene's. render_scene is this over
// a whole scene.
//
// `threads` > 1 (render --threads): each run of primitive commands between state or 2D
// commands is set up on that many threads, binned to screen regions (ref/region_bins.h)
// and the regions rasterized in parallel, each pixel's fragments in scene order: the
// framebuffer, its CRC and every stat equal the one-thread run's (docs/framebuffer.md,
// "Threads"). A fragment sink (pipeline order) or an inexact traversal (its coverage
// check is per triangle) keeps one thread; threads() says how many run.
//
// A primitives command with a texture bound (docs/texture.md) goes through the texture
// stage: whole 2x2 quads for the derivatives, its texel fetches through the texture
// cache in pipeline order, so it keeps one thread; `on_fragment` sees its fragments as
// they leave interpolation, before the texture stage.
//
// `st.hiz_mode` != off (depth.hiz, ref/hiz.h) where hiz_applies: coarse raster tests every
// tile against the bound table, which the ROP's depth writes and the clears update in
// pipeline order, so it keeps one thread; the image is the same.
//
// `memory.enabled` (memory.model != fixed): every ROP access and clear goes through the
// functional memory system (ref/memory/rop_memory.h), whose counts land in stats.memory
// at finish(); the access stream is in pipeline order, so it keeps one thread too.
//
// pipeline.mode = binned (ref/binning.h, docs/binning.md): set-up triangles and clears
// go to the Binner, which draws each bin's list with draw() at finish() or on overflow;
// one thread, and fragments reach `on_fragment` in bin order.
class SceneRenderer {
 public:
  SceneRenderer(const RasterState& arch, RenderStats& stats, const FragmentSink& on_fragment = {},
                int fb_tile_log2 = Framebuffer::kDefaultTileLog2, int threads = 1, const MemoryParams& memory = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;
  void run(std::span<const Command> commands);
  // A present (the trace's `frame`, docs/trace-format.md) without ending the run: the
  // framebuffer as drawn so far (unresolved), and the memory system's and texture unit's
  // counts up to here in the stats (the caches are not flushed: finish() writes them back).
  const Framebuffer& frame_so_far();
  // The functional memory system as it stands (memory.model = "fixed": null): its caches'
  // and fast-clear flags' state, which frame sampling's warm-up starts a timed run from.
  const RopMemory* memory() const;
  Framebuffer finish();
  int threads() const;  // the threads the pipeline runs on (1 with a fragment sink or scanline)
  // Sees every Hi-Z cull and accept (depth.hiz), before the tile is drawn.
  void set_hiz_observer(HizObserver observer);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One fragment as a line of the shared fragment-trace format: "x y z r g b s t" (decimal;
// s, t raw interp.texcoord_format, signed), followed by " mask" (decimal) when
// raster.samples > 1.
std::string fragment_trace_line(const Fragment& f);

}  // namespace rastsim
