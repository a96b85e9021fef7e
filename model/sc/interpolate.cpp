// SPDX-License-Identifier: Apache-2.0
#include "sc/interpolate.h"

#include <algorithm>
#include <vector>

#include "ref/pipeline.h"
#include "ref/rop.h"

namespace rastsim::sc {

namespace {
uint64_t quad_key(int x, int y) { return uint64_t(uint32_t(y >> 1)) << 32 | uint32_t(x >> 1); }
}  // namespace

// A textured batch's cycles: its 2x2 quads (pixels 2x..2x+1, 2y..2y+1) whole, helper
// pixels included (the RTL's fine raster closes the tile's mask over quads:
// rtl/rast_fine_raster.sv; docs/texture.md "RTL"), a row pair (pixel rows 2m, 2m + 1) at
// a time: the RTL interpolator never puts two row pairs in one beat (the texture stage's
// quad table), so each row pair of q quads costs interp_batch_cycles(4 q) (the same as
// ceil(4 Q / lanes) over the tile at 1, 2 or 4 lanes), with early Z too (the lanes compute
// the depth the early test takes). The beats go in frags.beats for the texture stage
// (FragmentBatch::Beats).
uint64_t Interpolate::textured_batch_cycles(FragmentBatch& frags, bool affine) {
  quad_keys_.clear();
  for (const PixelRun& r : frags.pixels->runs)
    for (int x = r.x0 & ~1; x < r.x1; x += 2) quad_keys_.push_back(quad_key(x, r.y));
  std::sort(quad_keys_.begin(), quad_keys_.end());
  const auto end = std::unique(quad_keys_.begin(), quad_keys_.end());
  FragmentBatch::Beats& b = frags.beats;
  b.lanes = p_.interp_lanes(affine);
  b.rows.clear();
  b.quad_x.clear();
  uint64_t cycles = 0;
  for (auto i = quad_keys_.begin(); i != end;) {  // keys sorted by row pair (the high word)
    auto j = i;
    while (j != end && (*j >> 32) == (*i >> 32)) ++j;
    b.rows.push_back({int32_t(*i >> 32), uint32_t(b.quad_x.size()), uint32_t(j - i), cycles});
    for (auto k = i; k != j; ++k) b.quad_x.push_back(int32_t(uint32_t(*k)));
    cycles += p_.interp_batch_cycles(4 * uint64_t(j - i), affine);
    i = j;
  }
  return cycles;
}

void Interpolate::body() {
  for (;;) {
    const PixelItem in = read(in_);
    if (early_ && in.state) early_state(*in.state);
    if (early_interlock_ && in.state) {  // its entry: every pixel, until the ROP ends it
      early_interlock_->sent_state();
      early_interlock_->fine(false, now());
    }
    if (!textured_ahead_ && pass_state(in, out_, p_.interp_pipeline_latency())) continue;
    if (in.state) {
      pass_state_behind_texture(in);
      continue;
    }
    const PixelBatch& batch = *in.work;
    const SetupTriangle& tri = *batch.tri;
    LocalPtr<FragmentBatch> frags = fragments_.take();
    frags->pixels = in.work;
    // At most one fragment a covered sample (ssaa), one a pixel otherwise.
    Fragment* const first = frags->reset(size_t(batch.pixels) * size_t(tri.samples));
    frags->count = shade(batch, first);
    if (early_interlock_) early_interlock_wait(batch);
    if (early_) early_test(*frags);
    ctx_.render.fragments_shaded += frags->kept();
    if (frags->count != 0) attribute_to(first->x, first->y);  // the batch's tile
    // Early Z: the lanes interpolate every fragment, culled or not: the early test takes
    // the depth they compute (docs/depth-culling.md "Early Z in the RTL"); a textured
    // batch its quads whole.
    const uint64_t cycles = tri.texture.enabled() ? textured_batch_cycles(*frags, tri.affine)
                                                  : p_.interp_batch_cycles(frags->count, tri.affine);
    if (!tri.affine) {  // a reciprocal a fragment (docs/clip-space.md, "Timing")
      ctx_.recip_reciprocals += frags->count;
      ctx_.recip_busy_cycles += cycles;
    }
    if (tri.texture.enabled()) {  // the texture stage starts on its first beat (sc/texture.h)
      textured_ahead_ = true;
      frags->beats.first = now() + 1 + p_.interp_pipeline_latency();
      write(texture_out_, FragmentItem{nullptr, std::move(frags)}, 1 + p_.interp_pipeline_latency());
      busy(cycles);
      continue;
    }
    busy(cycles);
    const uint64_t latency = behind_texture(now() + p_.interp_pipeline_latency());
    write(out_, FragmentItem{nullptr, std::move(frags)}, latency);
  }
}

size_t Interpolate::shade(const PixelBatch& batch, Fragment* const first) {
  const SetupTriangle& tri = *batch.tri;
  Fragment* out = first;
  if (shader_tri_ != batch.tri) {
    shader_tri_ = batch.tri;
    shader_.emplace(tri, frac_bits_);  // the reference's shading, fast path included
  }
  PixelShader& shader = *shader_;
  // Per batch, not per fragment: the stepped plane equations with no sink are the
  // common case and store fragments only, a run at a time.
  if (shader.stepped() && !ctx_.on_fragment) {
    for (const PixelRun& r : batch.runs)
      shader.shade_run(r.y, r.x0, [&](auto&& frag) {
        for (int x = r.x0; x < r.x1; ++x) *out++ = frag(x);
      });
    return size_t(out - first);
  }
  const bool dda = tri.interp_method != InterpMethod::Plane;
  for (const PixelRun& r : batch.runs) {
    for (int x = r.x0; x < r.x1; ++x) {
      shader.shade(x, r.y, r.mask, [&](const Fragment& f) {
        *out++ = f;
        // interp.method = dda: its error against the plane equations, counted as the
        // reference's render_scene counts it (same stats keys at both levels).
        if (dda) count_interp_error(f, interpolate_plane(tri, x, r.y, frac_bits_), ctx_.render);
        if (ctx_.on_fragment && !early_) ctx_.on_fragment(f);  // with early Z: the kept ones, early_test
      });
    }
  }
  return size_t(out - first);
}

// The reference's early test (ref/pipeline.cpp write: early_depth_cull with the tile's
// depth function) on each fragment in order against the depth the ROP will have then; a
// kept fragment's test and write applied to that copy as the ROP will apply them.
void Interpolate::early_test(FragmentBatch& frags) {
  EarlyZ& e = *early_;
  const PixelBatch& batch = *frags.pixels;
  const DepthFunc func = batch.hiz_accepted ? DepthFunc::Always : e.st.depth_func;
  if (frags.culled.size() < frags.count) frags.culled.resize(frags.count);
  size_t culled = 0;
  for (size_t k = 0; k < frags.count; ++k) {
    const Fragment& f = frags.storage[k];
    const bool cull = early_depth_cull(e.depth, f, func);
    frags.culled[k] = cull;
    if (cull) {
      ++culled;
      continue;
    }
    rop_write(e.depth, f, func, e.st.depth_write);
    if (ctx_.on_fragment) ctx_.on_fragment(f);
  }
  frags.culled_count = culled;
  // The work saved (ref/pipeline.cpp write): the attributes and, textured, a sample each.
  const bool textured = batch.tri->texture.enabled();
  ctx_.render.fragments_culled_early += culled;
  ctx_.render.interpolations_saved += culled * early_interpolations_saved(textured);
  ctx_.render.texture_samples_saved += textured ? culled : 0;
}

// Early Z's interlock (rast_early_z's rule): the batch enters the interpolator only once
// every earlier entry on its tile has ended at the ROP (free_at: the RTL's tile waits at
// the pixel FIFO's head until then, the stage starved); then its tile's entry.
void Interpolate::early_interlock_wait(const PixelBatch& batch) {
  const PixelRun& r = batch.runs.front();
  const int size = 1 << tile_log2_;
  const int x0 = r.x0 >> tile_log2_ << tile_log2_, y0 = r.y >> tile_log2_ << tile_log2_;
  const PixelRect fp{x0, y0, x0 + size, y0 + size};
  starve_until(early_interlock_->free_at(fp, now()) + 1);
  early_interlock_->sent(fp);
  early_interlock_->fine(false, now());
}

void Interpolate::early_state(const Command& cmd) {
  const auto* c = std::get_if<CmdClearDepth>(&cmd.body);
  if (!c) return;
  if (const auto z = quantize_unorm(c->z, early_->st.depth_bits))  // a bad value is the ROP's error to report
    early_->depth.clear_depth(*z);
}

// Stage::pass_state's issue cycle and latency, with the fence between them.
void Interpolate::pass_state_behind_texture(const PixelItem& in) {
  attribute_to_no_tile();
  busy(TimingParams::state_pass_cycles());
  const uint64_t latency = behind_texture(now() + p_.interp_pipeline_latency());
  write(out_, FragmentItem{in.state, {}}, latency);
}

uint64_t Interpolate::behind_texture(uint64_t ready) {
  if (textured_ahead_) {
    write(texture_out_, FragmentItem{});  // the fence
    read(texture_done_, false);           // starved until its token is back
    textured_ahead_ = false;
  }
  return ready > now() ? ready - now() : 0;
}

}  // namespace rastsim::sc
