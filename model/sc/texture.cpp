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
    // The RTL's datapath after the batch's last sample, net of its earlier start
    // (texture.latency_cycles): the ROP may start on the batch that much later.
    write(out_, FragmentItem{nullptr, std::move(out)}, p_.texture_latency);
  }
}

// The batch's fragments through the texture unit, in order (the reference's fetch order),
// and the work it took.
LocalPtr<const FragmentBatch> Texture::shade(const FragmentBatch& batch, TimingParams::TextureWork& work) {
  if (!unit_) {
    unit_.emplace(arch_.texture);
    unit_->on_fill = [this](uint64_t address, uint64_t bytes) { fill(address, bytes); };
  }
  if (quads_tri_ != batch.pixels->tri) next_triangle(batch.pixels->tri);
  const SetupTriangle& tri = *batch.pixels->tri;
  const TextureStats before = unit_->stats();
  const uint64_t quads_before = quads_.quads();
  LocalPtr<FragmentBatch> out = batches_.take();
  out->pixels = batch.pixels;
  Fragment* o = out->reset(batch.count);
  const int coord_frac = arch_.coord_format.frac_bits, tex_frac = arch_.texcoord_format.frac_bits;
  // The fills' places in the batch (fill()): a sample's texel requests, 1 (nearest) or 4.
  fetch_.slot = 0;
  fetch_.splits = 0;
  fetch_.per_request = tri.texture.filter == TexFilter::Nearest ? 1 : 4;
  // Every covered pixel's quad derivatives (the reference takes them before its early
  // test); a fragment early Z culled is not sampled and goes on as it came (its flag kept).
  for (size_t k = 0; k < batch.count; ++k) {
    const Fragment& f = batch.storage[k];
    const QuadDerivatives& d = quads_.derivatives(tri, f.x, f.y, coord_frac);
    if (batch.is_culled(k)) {
      *o++ = f;
      continue;
    }
    fetch_.base = unit_->stats().texel_fetches;
    fetch_.request = ~uint64_t{0};
    const uint64_t samples_before = unit_->stats().level_samples;
    *o++ = unit_->shade(f, d, tri.texture, tex_frac);
    fetch_.slot += unit_->stats().level_samples - samples_before;  // 1, or 2 where trilinear blends two levels
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
  work.miss_splits = fetch_.splits;
  return out;
}

// A line fill of the texture unit's cache, made in its fetch: where it falls in the batch
// as rast_texture_cache looks texels up (a request a sample slot, TimingParams::
// texture_cache_ports texels a cycle, a missing texel first in its cycle), and with
// memory.model = "dram" the fill through the memory system (timing/texture_memory_port.h).
void Texture::fill(uint64_t address, uint64_t bytes) {
  const uint64_t f = unit_->stats().texel_fetches - 1 - fetch_.base;  // the fetch in its fragment
  const uint64_t request = f / fetch_.per_request, pos = f % fetch_.per_request;
  if (request != fetch_.request) {  // a new request: its first lookup group starts at texel 0
    fetch_.request = request;
    fetch_.group = 0;
  }
  const uint64_t ports = p_.texture_cache_ports();
  const bool split = pos != fetch_.group + (pos - fetch_.group) / ports * ports;
  fetch_.group = pos;  // the missing texel's second lookup starts the next group
  fetch_.splits += split ? 1 : 0;
  if (mem_) mem_->fill(address, bytes, fetch_.slot + request, split);
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
