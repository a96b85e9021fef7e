// SPDX-License-Identifier: Apache-2.0
// ROP: depth test and colour/depth write of each fragment (ref/rop.h: rop_write), and
// the clears, in program order (ref/pipeline.h: apply_state_command). Owns the
// framebuffer (sparse tiles, ref/framebuffer.h, docs/framebuffer.md), which the 2D engine
// borrows and simulate_scene moves into its result. Timing does not follow the storage:
// a clear is charged for the whole W x H buffer, as below.
//
// - A batch of fragments takes ceil(A / rop.pixels_per_cycle) cycles, A the sum of
//   TimingParams::rop_accesses over its fragments: 1 a fragment with one sample or a full
//   mask (a fully covered pixel is written once: the compression rule), else one per
//   covered sample (ssaa fragments carry one sample each: 1 access).
// - A colour or depth clear takes ceil(W * H / rop.clear_pixels_per_cycle) cycles for
//   the W x H framebuffer, whatever raster.samples; viewport and scissor commands 1 cycle.
// - The end-of-frame marker (raster.samples = S > 1, SimContext::end_of_frame): the
//   resolve pass, TimingParams::resolve_cycles(W H, S) = ceil((W H S 4 + W H 4) /
//   rop.resolve_bytes_per_cycle) cycles; the framebuffer becomes the resolved one
//   (Framebuffer::resolve, as render_scene's).
// - A 2D command's marker: the ROP grants its framebuffer port to the 2D engine and
//   holds until the engine is done (sc/engine2d.h), then 1 cycle.
// - Counts fragments_passed, samples_passed, and the traffic (SimContext::rop_accesses,
//   framebuffer_bytes, resolve_cycles): framebuffer_bytes = accesses x (4 + depth
//   bytes) + (W H 4 a colour clear, W H depth bytes a depth clear) + resolve bytes.
// - Early Z (depth.early, sc/interpolate.h): a fragment culled early reaches the ROP
//   flagged, uncoloured; it takes its access slots (rop_accesses) for the early test's
//   depth reads only, in pipeline order (ref/rop.h early_depth_cull): the early test
//   shares the ROP's depth port, so the memory system sees the reference's stream.
//
// With the timed memory system (memory.model = "dram", attach_memory; docs/memory.md,
// "Timed memory system") every access also goes through the reference's functional
// caches (timing/rop_memory_port.h: RopMemoryPort). A batch then lasts as the RTL ROP's
// groups take (timing/memory_timing.h, memory_group_response: one group of
// rop.pixels_per_cycle accesses in flight, each answered when its fills have arrived;
// no fill: the cycles above); the resolve pass memory_transaction_cycles: its cycles,
// or until its last fill has arrived plus one cycle. Write-backs and clears' writes are
// posted.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "ref/framebuffer.h"
#include "sc/binning.h"
#include "sc/engine2d.h"
#include "sc/interpolate.h"
#include "timing/rop_memory_port.h"

namespace rastsim::sc {

class Rop : public Stage {
 public:
  static constexpr StageId kId = StageId::Rop;
  Rop(SimContext& ctx, const RasterState& arch, const TimingParams& p,
      Link<FragmentItem>& in, Link<PortGrant>& grant_2d, Link<PortGrant>& done_2d,
    sc_core::sc_module_name name = stage_name(kId).data());
  Framebuffer& framebuffer() { return fb_; }
  // Before the run: the ROP's accesses go through `mem` (the frame starts with the depth
  // clear the memory system sees, as render_scene's; with `warm`, from that functional
  // state instead, no clear: SimOptions::warm_memory).
  void attach_memory(MemorySystem& mem, const MemoryParams& p, const RopMemory* warm = nullptr);
  // After the run (cycle `end`): the frame end's accesses if the resolve did not make
  // them, every request drained; the functional counts (disabled without a memory).
  MemoryStats finish_memory(uint64_t end);
  // The memory port the 2D engine draws through while it holds the ROP's port (null:
  // memory.model = "fixed").
  RopMemoryPort* memory_port() { return mem_.get(); }
  // pipeline.mode = binned (before the run): the framebuffer is the tile buffer's samples
  // and every state command reaching the ROP (bin markers, the end of frame) is `bins`'
  // (sc/binning.h); no memory port: fragments stay on chip.
  void attach_bins(BinRop& bins) { bins_ = &bins; }

 private:
  void body() override;
  void command(const CommandPtr& cmd);
  // Cycles of a transaction starting now whose own work is `work_cycles`, after its
  // accesses (with a memory: its fills waited for).
  uint64_t transaction_cycles(uint64_t work_cycles) { return mem_ ? mem_->transaction_cycles(work_cycles, now()) : work_cycles; }
  RopMemory* functional_memory() { return mem_ ? &mem_->functional() : nullptr; }
  RasterState st_;
  Framebuffer fb_;
  uint64_t depth_bytes_;  // bytes of one depth value: ceil(raster.depth_bits / 8)
  const TimingParams& p_;
  Link<FragmentItem>& in_;
  Link<PortGrant>& grant_2d_;
  Link<PortGrant>& done_2d_;
  std::unique_ptr<RopMemoryPort> mem_;  // null: memory.model = "fixed"
  bool frame_finished_ = false;         // the resolve made the frame end's accesses
  BinRop* bins_ = nullptr;              // pipeline.mode = binned, else null
};

}  // namespace rastsim::sc
