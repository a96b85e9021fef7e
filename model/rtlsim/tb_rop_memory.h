// SPDX-License-Identifier: Apache-2.0
// The timed memory system behind the RTL ROP's memory port in co-simulation
// (memory.model = "dram"; docs/memory.md, "RTL co-simulation"): the SystemC model's
// MemorySystem, RopMemoryPort and DramModel (model/timing), driven by the testbench
// (testbench.cpp) as the SystemC ROP drives them (sc/rop.cpp), so both levels follow one
// timing rule (timing/memory_timing.h: memory_group_response) and make the same
// functional accesses.
//
// The functional accesses are the reference ROP's (ref/rop.h rop_write) on the fragments
// the RTL's fragment FIFO takes, in order, replayed on a framebuffer of its own (the
// state the reference's caches and depth compression see; the testbench's memory holds
// the RTL's writes): every hit, miss and byte equals render's. A fragment's accesses are
// made when the group of its first access reads (rast_rop.sv's groups: the read's lanes,
// one an access); the read's response comes when that group's fills have arrived.
// Clears at their command, the resolve's and the frame end's accesses as the SystemC ROP.
// The display's line fetch is the memory system's client `scanout` as in simulate
// (display/scanout_fetch.h): attached first, started at cycle 0 with double buffering and
// at the run's end with single buffering.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "display/scanout_fetch.h"
#include "ref/2d/draw2d.h"
#include "ref/framebuffer.h"
#include "ref/interpolate.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "rtlsim/cosim.h"
#include "timing/memory_system.h"
#include "timing/rop_memory_port.h"
#include "util/atomic_file.h"

namespace rastsim::rtlsim {

struct TbSetup;

class TbRopMemory {
 public:
  explicit TbRopMemory(const TbSetup& s);
  TbRopMemory(const TbRopMemory&) = delete;
  TbRopMemory& operator=(const TbRopMemory&) = delete;

  // A fragment the ROP's fragment FIFO took (in order).
  void fragment(const Fragment& f) { fragments_.push_back(f); }
  // The ROP's read of a group of `accesses` accesses, taken at core cycle `t`: the cycle
  // its response is due. `no_depth`: the group's tile was Hi-Z accepted, its fragments
  // tested with `always` (no depth read), as the reference's ROP tests them.
  uint64_t read(uint64_t t, uint32_t accesses, bool no_depth);
  // A 2D operation of `work` starting at core cycle `start` (the 2D engine draws through
  // the ROP's port: the colour client, as sc/engine2d.cpp): its accesses made, its fills
  // issued; returns the cycle its fills have been used (start + memory_transaction_cycles
  // with no work of its own): its last write may be taken from that cycle - 1.
  uint64_t operation_2d(const Draw2dWork& work, const Op2d& op, uint64_t start);
  // A state command taken at cycle `t` (a clear's bytes written).
  void command(const Command& cmd, uint64_t t);
  // The end-of-frame marker's command taken at cycle `t`: the resolve pass's cycles
  // (`resolve_cycles`, or until its last fill has arrived plus one cycle).
  uint64_t frame_end(uint64_t t, uint64_t resolve_cycles);
  // The run ended after `cycles` cycles: the frame end's accesses (if the resolve did not
  // make them), every request drained; the functional counts, the DRAM's figures and the
  // scan-out's (add_scanout_fetch_json) into `r`.
  void finish(uint64_t cycles, CosimResult& r);
  // The memory system, for the texel fetch port's fills (tb_texture.h).
  MemorySystem& system() { return system_; }

 private:
  MemorySystem system_;
  std::optional<AtomicFile> trace_;  // CosimOptions::mem_trace_path: committed by finish()
  std::unique_ptr<ScanoutFetch> scanout_;  // the display's line fetch (null: no display)
  Framebuffer shadow_;   // the reference ROP's framebuffer, replayed in stream order
  RasterState state_;
  RopMemoryPort port_;
  std::deque<Fragment> fragments_;  // taken by the fragment FIFO, not yet replayed
  uint64_t head_left_ = 0;          // accesses of the last replayed fragment not yet in a group
  bool frame_finished_ = false;     // the resolve made the frame end's accesses
  const MemoryStats* bin_stats_ = nullptr;  // binned: the reference's binning and tile_store counts
};

}  // namespace rastsim::rtlsim
