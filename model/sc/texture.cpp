// SPDX-License-Identifier: Apache-2.0
#include "sc/texture.h"

namespace rastsim::sc {

void Texture::body() {
  for (;;) {
    const FragmentItem in = read(in_);
    if (!in.work) {  // a fence: every batch before it is in the fragment FIFO
      write(done_, TextureFence{});
      continue;
    }
    const FragmentBatch& batch = *in.work;
    if (mem_) mem_->begin(now());  // the batch's fills from its first cycle
    TimingParams::TextureWork work;
    LocalPtr<const FragmentBatch> out = shade(batch, work);
    if (work.fragments != 0) attribute_to(batch.fragments().front().x, batch.fragments().front().y);
    if (mem_) {  // the misses' cost is the memory's: the fills' stall instead of texture.miss_cycles
      work.misses = 0;
      busy(p_.texture_batch_cycles(work) + mem_->stall_cycles());
    } else {
      busy(p_.texture_batch_cycles(work));
    }
    write(out_, FragmentItem{nullptr, std::move(out)});
  }
}

// The batch's fragments through the texture unit, in order (the reference's fetch order),
// and the work it took.
LocalPtr<const FragmentBatch> Texture::shade(const FragmentBatch& batch, TimingParams::TextureWork& work) {
  if (!unit_) {
    unit_.emplace(arch_.texture);
    if (mem_) mem_->attach(*unit_);
  }
  if (quads_tri_ != batch.pixels->tri) next_triangle(batch.pixels->tri);
  const SetupTriangle& tri = *batch.pixels->tri;
  const TextureStats before = unit_->stats();
  const uint64_t quads_before = quads_.quads();
  LocalPtr<FragmentBatch> out = batches_.take();
  out->pixels = batch.pixels;
  Fragment* o = out->reset(batch.count);
  const int coord_frac = arch_.coord_format.frac_bits, tex_frac = arch_.texcoord_format.frac_bits;
  // Every covered pixel's quad derivatives (the reference takes them before its early
  // test); a fragment early Z culled is not sampled and goes on as it came (its flag kept).
  for (size_t k = 0; k < batch.count; ++k) {
    const Fragment& f = batch.storage[k];
    const QuadDerivatives& d = quads_.derivatives(tri, f.x, f.y, coord_frac);
    *o++ = batch.is_culled(k) ? f : unit_->shade(f, d, tri.texture, tex_frac);
  }
  out->count = batch.count;
  if (batch.culled_count != 0) {
    out->culled.assign(batch.culled.begin(), batch.culled.begin() + std::ptrdiff_t(batch.count));
    out->culled_count = batch.culled_count;
  }
  quads_.add_covered(batch.pixels->pixels);
  const TextureStats& s = unit_->stats();
  work.quads = arch_.depth_early ? kept_quads(batch) : quads_.quads() - quads_before;
  work.bilinear_slots = s.level_samples - before.level_samples;
  work.texel_fetches = s.texel_fetches - before.texel_fetches;
  work.fragments = batch.kept();
  work.misses = s.cache_misses - before.cache_misses;
  return out;
}

// Early Z: the quads of the batch that hold a kept fragment and no earlier batch of the
// triangle had (the unit's timed work; helper_pixels still counts every covered pixel's
// quad, as the reference does).
uint64_t Texture::kept_quads(const FragmentBatch& batch) {
  uint64_t n = 0;
  for (size_t k = 0; k < batch.count; ++k) {
    if (batch.is_culled(k)) continue;
    const Fragment& f = batch.storage[k];
    n += kept_quads_.insert(uint64_t(uint32_t(f.y >> 1)) << 32 | uint32_t(f.x >> 1)).second;
  }
  return n;
}

// A new triangle's first batch: the last one's helper pixels counted, its quads dropped.
void Texture::next_triangle(const LocalPtr<const SetupTriangle>& tri) {
  unit_->stats().helper_pixels += quads_.helper_pixels();
  quads_.clear();
  kept_quads_.clear();
  quads_tri_ = tri;
}

void Texture::finish_texture() {
  if (!unit_) return;
  unit_->stats().helper_pixels += quads_.helper_pixels();
  quads_.clear();
  quads_tri_ = nullptr;
  ctx_.render.texture = unit_->stats();
}

}  // namespace rastsim::sc
