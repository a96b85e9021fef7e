// SPDX-License-Identifier: Apache-2.0
// pipeline.mode = binned in the timed model (docs/binning.md, "Timed model"): the
// binner, a stage between triangle setup and coarse raster, and the ROP's side of a bin.
//
//   command_fetch -> prim_assembly -> tri_setup -> binner -> coarse_raster -> fine_raster
//                 -> interpolate -> rop (the on-chip tile buffer)
//
// The decisions are the reference's (ref/binning.h, Binner, driven through its hooks):
// which bins list a triangle, the records and entries and their addresses
// (ref/memory/bin_memory.h), overflow, load/store flags and bytes. This layer adds time:
// - Binning pass: each set-up triangle costs max(1, C) binner cycles, C the bins its
//   clipped box overlaps (one candidate bin a cycle: bbox lists it, exact tests it); its
//   record and list entries are posted writes (client `binning`) at the start of those
//   cycles. A clear (one clear record) costs 1 cycle; viewport and scissor 1 cycle and
//   stop here (setup already clipped every box to them).
// - Render pass (at an overflow and at the end-of-frame marker, which command fetch
//   always sends in binned mode), bin by bin: the bin's list entries, its triangles'
//   records and the clear records it reads are issued together at the bin's start t0 and
//   the binner waits for the last (a list prefetch): busy max(0, last arrival - t0).
//   Then a begin marker (1 cycle), each clear record as a clear marker (1 cycle) and
//   each triangle (1 cycle) in record order down to coarse raster, which walks the
//   triangle's box clipped to the bin (the reference's draw(tri, walk)), and an end
//   marker (1 cycle). Markers pass the later stages as state commands do.
// - ROP: fragments write the tile buffer at rop.pixels_per_cycle accesses a cycle (the
//   immediate ROP's fixed-memory rule: no ROP cache, no DRAM). With R =
//   rop.resolve_bytes_per_cycle, the tile buffer's port:
//     begin: max(1, ceil(L / R), last load arrival - t0), L the bytes loaded (client
//            `tile_store` reads issued at t0 and waited for; none without a load);
//     clear: ceil(A / rop.clear_pixels_per_cycle), A the bin's pixels (on chip, no DRAM);
//     end:   max(1, ceil(S_b / R)), S_b the bytes stored (posted writes at the start); on
//            the last pass with raster.samples = S > 1 the per-bin resolve instead,
//            resolve_cycles(A, S) = ceil((A S 4 + A 4) / R), plus ceil(D / R) for D depth
//            bytes stored; resolve_cycles sums those of every bin.
//   The end-of-frame marker then costs 1 cycle (the image is already resolved bin by bin).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "ref/binning.h"
#include "ref/memory/bin_memory.h"
#include "sc/tri_setup.h"
#include "timing/memory_system.h"

namespace rastsim::sc {

// A marker of the render pass, down the triangle path from the binner to the ROP (a
// state command to the stages between; identified by bin_marker()).
struct BinMarker : Command {
  enum class Kind { Begin, Clear, End };
  Kind kind = Kind::Begin;
  PixelRect rect;                         // the bin's pixels (clipped to the screen)
  BinClear clear;                         // Clear: what it writes
  BinBytes bytes;                         // Begin: bytes loaded; End: bytes stored
  bool final_pass = false;                // End: the frame's last pass (colour resolved)
  std::vector<MemoryTransfer> transfers;  // the tile_store transfers (memory.model = dram)
};
// `c` as a bin marker, or null.
const BinMarker* bin_marker(const Command& c);
// Coarse raster's clip of the walk: a begin marker's bin, else `clip` unchanged.
inline PixelRect bin_walk_clip(const Command& state, const PixelRect& clip) {
  const BinMarker* m = bin_marker(state);
  return m && m->kind == BinMarker::Kind::Begin ? m->rect : clip;
}
// Binner cycles of a triangle whose box overlaps `candidates` bins.
inline uint64_t binning_triangle_cycles(uint64_t candidates) { return candidates > 0 ? candidates : 1; }

// The ROP's side: markers applied to its framebuffer (the tile buffer's samples) and
// timed by the rules above.
class BinRop {
 public:
  BinRop(SimContext& ctx, const TimingParams& p) : ctx_(ctx), p_(p) {}
  void attach_memory(MemorySystem& mem) { mem_ = &mem; }
  // Cycles of state command `cmd` (a marker or the end of frame) at the ROP at `now`.
  uint64_t command(const Command& cmd, Framebuffer& fb, uint64_t now);

 private:
  uint64_t port_cycles(uint64_t bytes) const { return (bytes + p_.rop_resolve_bytes_per_cycle - 1) / p_.rop_resolve_bytes_per_cycle; }
  SimContext& ctx_;
  const TimingParams& p_;
  MemorySystem* mem_ = nullptr;
  uint64_t resolve_cycles_ = 0;  // every bin's resolve so far
};

class BinnerStage : public Stage {
 public:
  // Its random stalls' stream (sc/stage.h): apart from every kStages row's.
  static constexpr int kStallStream = 100;
  // `memory`: memory.model != fixed (the binning and tile_store clients), else null.
  BinnerStage(SimContext& ctx, const RasterState& arch, const TimingParams& p, const MemoryParams* memory,
              Link<SetupItem>& in, Link<SetupItem>& out);
  // Setup's log of each triangle's command, in the order it writes them (for errors).
  std::deque<CommandPtr>& commands() { return commands_; }
  BinRop& rop_port() { return rop_; }
  // Before the run: the parameter buffer's and the bins' transfers become requests.
  void attach_memory(MemorySystem& mem);
  // After the run: the binning and tile_store clients' counts (render's memory stats).
  MemoryStats memory_stats() const;

 private:
  struct Step {  // one item of a bin's render: a triangle (held_ index) or a clear
    bool clear = false;
    uint32_t tri = 0;
    BinClear value;
  };
  void body() override;
  void state(const CommandPtr& cmd);
  template <class F>
  void binner_call(F&& f);  // a Binner call, and held_ kept in step with it
  void begin_bin(const PixelRect& r, BinBytes load);
  void play_bin(const PixelRect& r, bool final_pass, BinBytes store);
  void send(LocalPtr<BinMarker> m);

  RasterState st_;
  const TimingParams& p_;
  Link<SetupItem>& in_;
  Link<SetupItem>& out_;
  Framebuffer no_fb_;  // the Binner's, never written: the ROP applies clears (hooks)
  std::optional<BinMemory> bin_mem_;
  std::optional<Binner> binner_;
  MemorySystem* mem_ = nullptr;
  BinRop rop_;
  std::deque<CommandPtr> commands_;
  std::vector<LocalPtr<const SetupTriangle>> held_;  // Binner::held()'s, shared with the stages below
  // The bin being rendered, gathered between the Binner's begin_bin and end_bin hooks.
  PixelRect rect_;
  BinBytes load_;
  std::vector<Step> steps_;
  std::vector<MemoryTransfer> reads_, tile_;  // binning reads; tile_store loads and stores
};

}  // namespace rastsim::sc
