// SPDX-License-Identifier: Apache-2.0
#include "sc/texture.h"

#include <algorithm>
#include <bit>

namespace rastsim::sc {

void Texture::body() {
  for (;;) {
    const FragmentItem in = read(in_);
    if (!in.work) {  // a fence: every batch before it is in the fragment FIFO
      write(done_, TextureFence{});
      continue;
    }
    const FragmentBatch& batch = *in.work;
    start_ = now();  // its first beat's arrival (sc/interpolate.h), or the previous batch's end
    if (mem_) mem_->begin(start_);  // the batch's fills from its first cycle
    TimingParams::TextureWork work;
    LocalPtr<const FragmentBatch> out = shade(batch, work);
    if (work.fragments != 0) attribute_to(batch.fragments().front().x, batch.fragments().front().y);
    if (mem_) {  // the misses' cost is the memory's: the fills' stall instead of texture.miss_cycles
      work.misses = 0;
      busy(p_.texture_batch_cycles(work) + fetch_.wait + mem_->stall_cycles());
    } else {
      busy(p_.texture_batch_cycles(work) + fetch_.wait);
    }
    // The RTL's datapath after the batch's last sample (texture.latency_cycles): the ROP
    // may start on the batch that much later.
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
  fetch_.wait = 0;
  beat_arrivals(batch);
  // Every covered pixel's quad derivatives (the reference takes them before its early
  // test); a fragment early Z culled is not sampled and goes on as it came (its flag kept).
  for (size_t k = 0; k < batch.count; ++k) {
    const Fragment& f = batch.storage[k];
    const QuadDerivatives& d = quads_.derivatives(tri, f.x, f.y, coord_frac);
    if (batch.is_culled(k)) {
      *o++ = f;
      continue;
    }
    fetch_.wait += slot_wait(batch, k, tri, unit_->stats().cache_misses - before.cache_misses);
    fetch_.base = unit_->stats().texel_fetches;
    fetch_.request = ~uint64_t{0};
    const uint64_t samples_before = unit_->stats().level_samples;
    *o++ = unit_->shade(f, d, tri.texture, tex_frac);
    fetch_.slot += unit_->stats().level_samples - samples_before;  // 1, or 2 where trilinear blends two levels
  }
  // The beats after the last kept fragment: a batch early Z culled whole adds all of its
  // own to those the serialiser still has to pass (each a cycle, as rast_texture_stage).
  trailing_empty_ =
      batch.kept() == 0 ? trailing_empty_ + covered_.size() : empty_beats(prev_beat_ + 1, covered_.size());
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
  if (mem_) mem_->fill(address, bytes, fetch_.slot + fetch_.wait + request, split);
}

// The beat that completes each fragment's quad (the quad table's bottom-left pixel for a
// top-row fragment, its own for a bottom-row one) and its arrival, from the
// interpolator's beats (FragmentBatch::Beats: a row pair's pixels row-major, top row
// first). Fragments and row pairs are both in row order.
void Texture::beat_arrivals(const FragmentBatch& batch) {
  const FragmentBatch::Beats& b = batch.beats;
  arrive_.assign(batch.count, b.first);
  beat_.assign(batch.count, 0);
  uint64_t beats = 0;
  for (const FragmentBatch::RowPair& rp : b.rows) beats = rp.beat + (4 * uint64_t(rp.quads) + b.lanes - 1) / b.lanes;
  covered_.assign(beats, 0);
  size_t r = 0;
  for (size_t k = 0; k < batch.count && !b.rows.empty(); ++k) {
    if (batch.is_culled(k)) continue;
    const Fragment& f = batch.storage[k];
    while (r + 1 < b.rows.size() && b.rows[r].pair < (f.y >> 1)) ++r;
    const FragmentBatch::RowPair& rp = b.rows[r];
    const auto first = b.quad_x.begin() + rp.first_quad;
    const uint64_t i = uint64_t(std::lower_bound(first, first + rp.quads, f.x >> 1) - first);
    const uint64_t pixel = 2 * uint64_t(rp.quads) + 2 * i + ((f.y & 1) ? uint64_t(f.x & 1) : 0);
    arrive_[k] = b.first + rp.beat + pixel / b.lanes;
    const uint64_t own = 2 * (f.y & 1 ? uint64_t(rp.quads) : 0) + 2 * i + uint64_t(f.x & 1);
    beat_[k] = rp.beat + own / b.lanes;
    covered_[beat_[k]] = 1;
  }
}

// rast_texture_stage's serialiser takes a covered lane a cycle, and a cycle for a beat with
// none (helper pixels only): the beats without a covered lane from `from` to `to` (not
// included).
uint64_t Texture::empty_beats(uint64_t from, uint64_t to) const {
  uint64_t n = 0;
  for (uint64_t j = from; j < to && j < covered_.size(); ++j) n += covered_[j] ? 0 : 1;
  return n;
}

// rast_texture_stage's head (docs/texture.md "Timed texture stage"): fragment k is loaded
// into the serialiser's hold a cycle after its quad's beat arrived and leaves it when the
// next covered fragment loads (the tile's last: a cycle later), then kBeatToRequest
// cycles to its first sample slot. A mipmapped texture of another size than the level
// table's holds it while the table fills, a level a cycle, after the fragments ahead have
// passed the level sequencer. Returns how long the slot stream waits for it.
uint64_t Texture::slot_wait(const FragmentBatch& batch, size_t k, const SetupTriangle& tri, uint64_t misses) {
  const uint64_t stall = mem_ ? mem_->stall_cycles() : misses * p_.texture_miss_cycles;
  const uint64_t next_slot = start_ + fetch_.slot + fetch_.wait + fetch_.splits + stall;
  size_t n = k + 1;
  while (n < batch.count && batch.is_culled(n)) ++n;
  uint64_t held = arrive_[k] + 1, table = 0;
  const TextureImage& img = *tri.texture.image;
  const int side = std::max(img.width, img.height);
  if (tri.texture.mipmap && side > 1 && (img.width != table_w_ || img.height != table_h_)) {
    const uint64_t fill = uint64_t(std::bit_width(uint32_t(side)));  // levels W x H .. 1 x 1
    held += fill + 1;
    table = next_slot + fill + kTableToSlot;
    table_w_ = img.width;
    table_h_ = img.height;
  }
  uint64_t ready = std::max(std::max(held, n < batch.count ? arrive_[n] : 0) + kBeatToRequest, table);
  // The serialiser: a cycle after the fragment before, and one for each beat between them
  // without a covered lane (the batch's first: the last batch's trailing such beats too).
  const bool first = k == 0 || fetch_.slot == 0;
  const uint64_t empty = first ? trailing_empty_ + empty_beats(0, beat_[k]) : empty_beats(prev_beat_ + 1, beat_[k]);
  if (serial_ != 0) ready = std::max(ready, serial_ + 1 + empty);
  prev_beat_ = beat_[k];
  serial_ = std::max(ready, next_slot);
  return ready > next_slot ? ready - next_slot : 0;
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
