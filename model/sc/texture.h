// SPDX-License-Identifier: Apache-2.0
// The texture stage (docs/texture.md, "Timed texture stage"): the reference texture unit
// (ref/texture/texture_unit.h: level of detail, addressing, filters, texenv, the texture
// cache) on each textured batch of interpolated fragments, timed.
//
// - Beside the triangle path: interpolation sends it the batches of triangles drawn with a
//   texture bound (sc/interpolate.h) and every other transaction straight to the ROP, so an
//   untextured scene never reaches this stage and is timed as without it.
// - A batch's fragments are shaded in order, with their 2x2 quad's coarse derivatives
//   (ref TriangleQuads, one a triangle: helper pixels counted as the reference counts
//   them), and the shaded batch goes to the ROP's fragment FIFO.
// - Cost: TimingParams::texture_batch_cycles on the batch's quads, bilinear sample slots,
//   texel fetches, fragments and texture-cache line misses: with memory.model = "fixed"
//   texture.miss_cycles a miss; with memory.model = "dram" (attach_memory) each miss is a
//   blocking line fill through the memory system (timing/texture_memory_port.h: the batch
//   is busy the miss-free cycles plus the stall until each fill has arrived), made at its
//   sample's slot in the batch as the RTL's texture cache makes it (fill()).
// - The start on the first beat (as rast_texture_stage): the batch arrives when its first
//   beat does (FragmentBatch::Beats, the interpolator's), and each fragment's first sample
//   slot waits for the beat completing its quad, the next fragment's beat (the
//   serialiser's hold), the serialiser's one covered lane a cycle (a cycle a helper-only
//   beat) and a level table fill (a mipmapped texture of a new size): slot_wait(); the
//   batch is busy from its start to its last slot.
// - Latency: the shaded batch is ready for the ROP texture.latency_cycles after the
//   batch's cycles (Stage::write's extra latency; the stage is not busy meanwhile).
// - A fence (a transaction without a batch) from interpolation: every batch before it is
//   in the fragment FIFO, so one token goes back on texture_done, at 0 cycles; interpolation
//   writes its next untextured transaction behind it (the ROP takes them in order).
// - Counts RenderStats::texture (docs/stats.md) at the end of the run (finish()).
#pragma once

#include <optional>

#include <memory>
#include <unordered_set>
#include <vector>

#include "ref/texture/texture_unit.h"
#include "sc/interpolate.h"
#include "timing/texture_memory_port.h"

namespace rastsim::sc {

class Texture : public Stage {
 public:
  static constexpr StageId kId = StageId::Texture;
  // rast_texture_stage's depths (docs/texture.md "Timed texture stage"), cycles: from a
  // fragment's leaving the serialiser's hold to its first sample slot, the LOD unit (3)
  // and the address unit (4), plus the beat FIFO's (1); from the last sample slot ahead
  // of a level table fill to the waiting fragment's first slot, the table's start (2),
  // the LOD unit's (3) less the address unit's slot (1).
  static constexpr uint64_t kBeatToRequest = 8, kTableToSlot = 4;
  Texture(SimContext& ctx, const RasterState& arch, const TimingParams& p, Link<FragmentItem>& in,
          Link<FragmentItem>& out, Link<TextureFence>& done, sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), arch_(arch), p_(p), in_(in), out_(out), done_(done) {}
  // memory.model = "dram" (before the run): the cache's misses become line fills through
  // `mem` (the texture client), which must outlive the run.
  void attach_memory(MemorySystem& mem) { mem_ = std::make_unique<TextureMemoryPort>(mem); }
  // The texture client's figures (null without attach_memory).
  const TextureMemoryPort* memory_port() const { return mem_.get(); }
  // After the run: the last triangle's helper pixels, and the unit's counts into the
  // context's RenderStats::texture (all 0 when nothing was textured).
  void finish_texture();

 private:
  void body() override;
  LocalPtr<const FragmentBatch> shade(const FragmentBatch& batch, TimingParams::TextureWork& work);
  void next_triangle(const LocalPtr<const SetupTriangle>& tri);
  uint64_t kept_quads(const FragmentBatch& batch);
  void fill(uint64_t address, uint64_t bytes);  // TextureUnit::on_fill
  // The beats' arrivals (FragmentBatch::Beats): arrive_[k] the cycle the beat completing
  // fragment k's quad reaches the stage.
  void beat_arrivals(const FragmentBatch& batch);
  // Cycles the slot stream waits before fragment k's first level sample (its beats, the
  // level table's fill); `misses` the batch's line misses so far.
  uint64_t slot_wait(const FragmentBatch& batch, size_t k, const SetupTriangle& tri, uint64_t misses);

  const RasterState& arch_;
  const TimingParams& p_;
  std::unique_ptr<TextureMemoryPort> mem_;  // memory.model = "dram", else null
  Link<FragmentItem>& in_;
  Link<FragmentItem>& out_;
  Link<TextureFence>& done_;
  Recycler<FragmentBatch> batches_;       // the shaded batches (sc/recycler.h)
  std::optional<TextureUnit> unit_;       // created at the first textured batch, as the reference's
  TriangleQuads quads_;                   // the current triangle's quads
  std::unordered_set<uint64_t> kept_quads_;  // early Z: its quads with a kept fragment (y/2 << 32 | x/2)
  LocalPtr<const SetupTriangle> quads_tri_;  // held: its address identifies the triangle
  // Where the unit's fetches are in the batch being shaded (fill()): the fragment's first
  // fetch and sample slot, texels a request, the request and lookup group of the last
  // miss, the batch's split lookup groups.
  // wait: the cycles the batch's sample slots waited for its beats and the level table.
  struct FetchPlace {
    uint64_t base = 0, slot = 0, per_request = 1, request = 0, group = 0, splits = 0, wait = 0;
  } fetch_;
  uint64_t start_ = 0;              // the batch's first cycle (its read)
  std::vector<uint64_t> arrive_;    // beat_arrivals()
  std::vector<uint64_t> beat_;      // fragment k's own beat in the batch
  std::vector<uint8_t> covered_;    // beat j holds a covered (kept) lane
  uint64_t empty_beats(uint64_t from, uint64_t to) const;
  // The serialiser (slot_wait): the last fragment's first slot (0: none yet), its beat,
  // and the empty beats the last batch ended with.
  uint64_t serial_ = 0, prev_beat_ = 0, trailing_empty_ = 0;
  // The level table's texture size (rast_texture_stage's key_w_q, key_h_q; 0: never filled).
  int table_w_ = 0, table_h_ = 0;
};

}  // namespace rastsim::sc
