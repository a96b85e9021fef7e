// SPDX-License-Identifier: Apache-2.0
// Attribute interpolation: colour and depth of each covered pixel (ref/interpolate.h:
// shade_pixel), a tile's batch at a time.
//
// - Each pixel gives its fragments by shade_pixel: one (one sample, or msaa: centre-
//   shaded, carrying the pixel's mask), or one per covered sample (ssaa).
// - A batch shading N fragments takes ceil(N / interp.fragments_per_cycle) cycles, a
//   perspective-correct (non-affine) triangle's ceil(N / min(interp.fragments_per_cycle,
//   recip.lanes)) (TimingParams::interp_batch_cycles); its fragments are ready for the
//   ROP TimingParams::interp_pipeline_latency() later: the divider pipeline
//   (interp.latency_cycles) plus, with interp.perspective, the reciprocal unit's stages,
//   for every triangle (docs/clip-space.md, "Timing").
// - Counts fragments_shaded, and the reciprocal unit's work (SimContext::recip_reciprocals,
//   one a fragment of a non-affine triangle; recip_busy_cycles, its batches' cycles).
// - Every fragment leaving here goes to the fragment sink, in order: the same stream
//   (ref/pipeline.h: fragment_trace_line) as the reference model's.
// - A one-sample triangle shaded by plane equations goes run by run through
//   PixelShader::shade_run, the reference's run path (ref/pipeline.cpp, RunWriter): a
//   flat-shaded run is one fragment with its x moved along.
// - A batch of a triangle drawn with a texture bound goes to the texture stage
//   (sc/texture.h) on the texture FIFO as the interpolator starts it, ready at its first
//   beat, with its beats (FragmentBatch::Beats); everything else to the ROP on the fragment FIFO,
//   after a fence when textured batches are ahead of it: the fence goes down the texture
//   FIFO, its token comes back on texture_done (starved until then) and the transaction
//   enters the fragment FIFO behind them, ready no earlier than its own pipeline allows.
//   Without textures this path is never taken: the stage is timed as without a texture stage.
// - Early Z (depth.early, docs/depth-culling.md "Early Z in the timed model"): each
//   fragment's depth is tested before its attributes are used, in order, against a copy
//   of the depth buffer as the ROP will have it (functional-first, zero lag); a fragment
//   failing at every covered sample is culled (fragments_culled_early,
//   interpolations_saved, texture_samples_saved as the reference counts them): it stays in
//   the batch flagged, for its depth reads at the ROP's port, and costs no sample at the
//   texture stage. Its lane it still takes: the lanes compute the depth the test uses
//   (rtl/rast_early_z.sv tests the interpolator's output), so the batch takes
//   interp_batch_cycles(every fragment). The interlock (as the RTL's): a batch is read and
//   then waited on (starved) until no batch or state item on its tile is in flight to
//   the ROP's end (early_interlock_wait; docs/depth-culling.md "Early Z in the RTL").
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "ref/interpolate.h"
#include "sc/fine_raster.h"
#include "sc/hiz_interlock.h"
#include "sc/recycler.h"

namespace rastsim::sc {

// One batch's fragments, in pixel order, and the pixel batch they came from (held, not
// copied: its runs). The storage only grows (a recycled batch keeps it, sc/recycler.h),
// so shading writes fragments in place without a capacity check each.
struct FragmentBatch {
  LocalPtr<const PixelBatch> pixels;  // the runs shaded (sc/fine_raster.h)
  // One fragment a pixel (the triangle has one sample): fragment k of the batch is the
  // k-th pixel of pixels->runs, so the ROP can write a run at a time (ref/rop.h:
  // rop_write_run).
  bool one_per_pixel() const { return pixels->tri->samples == 1; }
  std::span<const Fragment> fragments() const { return {storage.data(), count}; }
  // Empties the batch and returns room for `n` fragments (set `count` once written).
  Fragment* reset(size_t n) {
    if (storage.size() < n) storage.resize(n);
    count = 0;
    culled_count = 0;
    return storage.data();
  }
  // Early Z (depth.early): fragment k failed the early depth test when culled[k] != 0
  // (valid only when culled_count > 0). A culled fragment stays in the batch, in pixel
  // order, uncoloured: the texture stage skips it and the ROP makes only its depth reads
  // (ref/rop.h early_depth_cull), so the memory system sees the reference's access stream.
  bool is_culled(size_t k) const { return culled_count != 0 && culled[k] != 0; }
  size_t kept() const { return count - culled_count; }
  std::vector<Fragment> storage;
  size_t count = 0;  // fragments in storage[0, count)
  std::vector<uint8_t> culled;
  size_t culled_count = 0;
  // A textured batch's beats, as the interpolator sends them (Interpolate::
  // textured_batch_cycles; the texture stage starts on the first, sc/texture.h): its 2x2
  // quads whole, a row pair (pixel rows 2m, 2m + 1) at a time in row order, each row pair
  // row-major (its top row's quad columns left to right, then its bottom row's), `lanes`
  // pixels a beat, a row pair starting a beat; beat b reaches the texture stage at cycle
  // first + b.
  struct RowPair {
    int32_t pair;                // y / 2
    uint32_t first_quad, quads;  // its quad columns: quad_x[first_quad, first_quad + quads)
    uint64_t beat;               // its first beat in the batch
  };
  struct Beats {
    uint64_t first = 0, lanes = 1;  // cycle; pixels a beat
    std::vector<RowPair> rows;
    std::vector<int32_t> quad_x;    // x / 2, ascending in each row pair
  } beats;
};
using FragmentItem = Item<LocalPtr<const FragmentBatch>>;

// Texture stage -> interpolation: every textured batch before the fence has left
// (sc/texture.h).
struct TextureFence {};

class Interpolate : public Stage {
 public:
  static constexpr StageId kId = StageId::Interpolate;
  Interpolate(SimContext& ctx, const RasterState& arch, const TimingParams& p,
              Link<PixelItem>& in, Link<FragmentItem>& out, Link<FragmentItem>& texture_out,
              Link<TextureFence>& texture_done, sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), frac_bits_(arch.coord_format.frac_bits), p_(p), in_(in), out_(out),
        texture_out_(texture_out), texture_done_(texture_done) {
    if (arch.depth_early) early_.emplace(arch);
    // Its interlock (as rast_early_z's) where the test reads the stored depth; not in the
    // binned pipeline (which refuses early Z).
    if (arch.depth_early && arch.depth_func != DepthFunc::Always && arch.bin.mode != PipelineMode::Binned) {
      early_interlock_ = std::make_unique<HizInterlock>(1, ctx_);
      ctx_.early_interlock = early_interlock_.get();
      tile_log2_ = std::countr_zero(unsigned(arch.tile_size));
    }
  }
  // Before the run, with depth.early: the depth the frame starts with (the ROP's).
  void start_early_depth(const Framebuffer& fb) {
    if (early_) early_->depth = fb;
  }

 private:
  void body() override;
  // Shades the batch's fragments into `out` (one a covered sample at most); their count.
  size_t shade(const PixelBatch& batch, Fragment* out);
  // Early Z: marks the batch's fragments that fail the depth test (counted); shows the
  // kept ones to the fragment sink.
  void early_test(FragmentBatch& frags);
  // A state command on the early test's copy of the depth buffer (a depth clear).
  void early_state(const Command& cmd);
  // Early Z's interlock: waits until the batch's tile has nothing in flight to the ROP's
  // end, then records its entry (docs/depth-culling.md "Early Z in the RTL").
  void early_interlock_wait(const PixelBatch& batch);
  // A state command with textured batches ahead: its issue cycle, then behind them.
  void pass_state_behind_texture(const PixelItem& in);
  // The fence, when textured batches are ahead; then the extra latency that makes a
  // transaction whose pipeline ends at cycle `ready` ready then (0 when already past).
  uint64_t behind_texture(uint64_t ready);
  // A textured batch's cycles in the lanes: its 2x2 quads whole, helper pixels included,
  // a row pair at a time; under early Z the quads of the kept fragments only. Records
  // the beats in frags.beats (all but their first cycle).
  uint64_t textured_batch_cycles(FragmentBatch& frags, bool affine);
  int frac_bits_;
  const TimingParams& p_;
  Link<PixelItem>& in_;
  Link<FragmentItem>& out_;
  Link<FragmentItem>& texture_out_;    // textured batches and fences, to the texture stage
  Link<TextureFence>& texture_done_;   // a fence's token back
  bool textured_ahead_ = false;        // a textured batch was sent since the last fence
  Recycler<FragmentBatch> fragments_;  // no allocation a batch (sc/recycler.h)
  std::vector<uint64_t> quad_keys_;    // textured_batch_cycles' scratch: y/2 << 32 | x/2
  // The shader of the last batch's triangle, kept for its next tiles (the reference
  // builds one a triangle too: PlaneStepper's setup divides). Holding the triangle keeps
  // its pooled object from being reused, so the address identifies it.
  LocalPtr<const SetupTriangle> shader_tri_;
  std::optional<PixelShader> shader_;
  // Early Z (depth.early, docs/depth-culling.md "Early Z in the timed model"): the depth
  // buffer as the ROP will have it at each fragment, functional-first (zero lag: the
  // ROP's writes of the fragments ahead applied here at once, in pipeline order).
  struct EarlyZ {
    explicit EarlyZ(const RasterState& a)
        : st(a), depth(a.fb_width, a.fb_height, a.samples) {
      depth.clear_depth(static_cast<uint32_t>((uint64_t{1} << a.depth_bits) - 1));  // as the ROP's
    }
    RasterState st;
    Framebuffer depth;  // colour unused
  };
  std::optional<EarlyZ> early_;
  // Early Z's interlock (rast_early_z's rule, pixel blocks): entries a batch or state item
  // from here to the ROP's end of it; null without. tile_log2_: raster.tile_size's log2.
  std::unique_ptr<HizInterlock> early_interlock_;
  int tile_log2_ = 0;
};

}  // namespace rastsim::sc
