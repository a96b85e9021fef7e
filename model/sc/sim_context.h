// SPDX-License-Identifier: Apache-2.0
// SimContext: what every stage of one simulation shares: the cycle time, the reference
// model's counters (filled by the stage that owns each), the fragment sink, tracing and
// stall-injection switches, and the first error raised by any stage.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>

#include <systemc>

#include "ref/pipeline.h"
#include "sc/local_ptr.h"

namespace rastsim::sc {

// A command as the stages hold it. A streamed scene's commands live in their batch,
// which these pointers share: a batch is freed when the last transaction that names one
// of its commands is gone (state markers, 2D commands, triangles in flight). A whole
// Scene's commands are borrowed (no owner, the caller keeps the Scene). A LocalPtr
// (sc/local_ptr.h): counted on the simulation's thread only.
using CommandPtr = LocalPtr<const Command>;
inline CommandPtr borrow_command(const Command& c) { return CommandPtr(nullptr, &c); }

class HizInterlock;  // sc/hiz_interlock.h
class HizFlush;      // sc/hiz_flush.h

struct SimContext {
  // One core clock cycle is one simulated nanosecond; clock.core_mhz only converts cycle
  // counts to seconds in the stats, so cycle counts are exact integers at any clock.
  const sc_core::sc_time cycle{1, sc_core::SC_NS};

  bool tracing = false;  // stages update their VCD state signals only when true
  // Stages wait for SystemC time to reach their own before each step, instead of running
  // ahead of it (sc/stage.h): for the VCD and the timeline, which record changes in time
  // order, and for tests that check a decoupled run against a lock-step one. The cycles
  // and stats are the same either way.
  bool lockstep = false;
  // memory.model = "dram" with a texture bound: the memory clients of different processes
  // (the ROP, the texture stage, the 2D engine, the Hi-Z table) make each DRAM request
  // only once SystemC time has reached its cycle (MemorySystem::set_arrival_wait), so
  // their requests enter the DRAM in time order, as a memory controller sees them
  // (docs/memory.md, "Arbitration"). Set by command fetch at the first textured draw, in
  // binned mode (the binner and the ROP) and by coarse raster with a spilled Hi-Z table's
  // flush engine: other runs have one such client at a time and run ahead as before.
  bool memory_time_order = false;
  // Links wake a writer waiting on a full FIFO at the first free slot, not once it is
  // empty (sc/link.h): in lock-step, and wherever memory_time_order is set (textured,
  // binned, a spilled Hi-Z table's flush), where a writer woken late would make its memory
  // requests after SystemC time passed their cycles, out of time order (a decoupled run
  // then disagreed with a lock-step one).
  bool wake_writers_at_free_slot = false;

  // Random stall injection (tests): before each FIFO write, with this probability, the
  // writer waits 1..stall_max_cycles extra cycles. Seeded; never changes the image.
  uint64_t stall_seed = 0;
  double stall_probability = 0;
  int stall_max_cycles = 8;

  RenderStats render;       // the same counters as the reference model, stage by stage
  // The ROP's framebuffer traffic (docs/microarchitecture.md, "Multisampling"): accesses
  // (TimingParams::rop_accesses summed over every fragment), bytes moved, and the cycles
  // of the frame-end resolve pass.
  uint64_t rop_accesses = 0, framebuffer_bytes = 0, resolve_cycles = 0;
  // The interpolator's reciprocal unit (sc/interpolate.h): reciprocals computed, cycles busy.
  uint64_t recip_reciprocals = 0, recip_busy_cycles = 0;
  // The end-of-frame marker: with raster.samples > 1 command fetch sends it after the
  // last command, down the triangle path like a state command; the ROP resolves on it.
  // Identified by address; its body is never applied.
  const Command end_of_frame{CmdScissor{}, SourceLoc{"end of frame", 0}};
  bool is_end_of_frame(const Command* c) const { return c == &end_of_frame; }
  bool is_end_of_frame(const CommandPtr& c) const { return c.get() == &end_of_frame; }
  FragmentSink on_fragment;  // sees each fragment leaving interpolation, in order
  // Hi-Z's interlock (coarse raster's, with a table): fine raster and the ROP record the
  // ends of the tiles and state items it sent. Null without.
  HizInterlock* hiz_interlock = nullptr;
  // Sees coarse raster's every Hi-Z cull and accept (tests: a lagged run's culls must be
  // the reference's), and the planted bug of the lagged tests (an accept on busy blocks).
  std::function<void(const SetupTriangle& t, const PixelRect& fp, HizDecision d)> on_hiz;
  bool hiz_lag_accept_busy = false;
  // Early Z's interlock (the interpolator's, depth.early with a depth function that reads:
  // sc/interpolate.h), on pixels: the ROP records the ends of the batches and state items
  // it was sent. Null without.
  HizInterlock* early_interlock = nullptr;
  // Hi-Z's flush engine (memory.model = dram with spilled blocks, sc/hiz_flush.h): the ROP
  // hands it each drawn tile's writes to spilled blocks. Null without.
  HizFlush* hiz_flush = nullptr;
  // Sees command fetch start each transaction (a command, or triangle k of a primitive
  // command) at `cycle`, in program order (the sampled level's unit boundaries).
  std::function<void(const Command& cmd, size_t triangle, uint64_t cycle)> on_fetch;
  // Sees the ROP take each state item of the scene (a clear, viewport, scissor or 2D
  // command's marker; not the end-of-frame marker, nor a binned run's) at `cycle`, its
  // first cycle, in program order (frame sampling's frame boundaries at the ROP).
  std::function<void(const Command& cmd, uint64_t cycle)> on_rop_state;

  std::exception_ptr error;  // first exception raised in any stage (null when none)

  uint64_t to_cycles(const sc_core::sc_time& t) const { return t.value() / cycle.value(); }
  // Records the first exception and stops the simulation; rethrow_failure() raises it
  // again after sc_start, with its type (SceneError, ModelError, ...) intact.
  void fail(std::exception_ptr e) {
    if (!error) error = std::move(e);
    sc_core::sc_stop();
  }
  void rethrow_failure() const {
    if (error) std::rethrow_exception(error);
  }
};

}  // namespace rastsim::sc
