// SPDX-License-Identifier: Apache-2.0
// Stage: the base of every pipeline stage module. One SC_THREAD runs the stage's body();
// the helpers below are the only places time passes, and they account it:
//
// - read():  blocks on the input FIFO, then until the transaction is ready -> starved
//            (read(in, false): a further input of the transaction in progress, as the
//            2D engine's grant or the ROP's 2D done: starved, no new transaction)
// - busy(n): n cycles of one transaction's work                            -> busy
// - write(): blocks on a full output FIFO (plus injected stalls)           -> stalled
//
// Every cycle of a stage is exactly one of busy, stalled or starved, so the three add
// up to the simulated cycle count.
//
// Time: each stage keeps its own cycle count (now()), advanced by these helpers from the
// timestamps its Links give (sc/link.h), never by waiting for SystemC time: a stage runs
// ahead of the SystemC clock until it must block on an empty input or a full output
// (temporal decoupling, exact because a FIFO's timing depends only on those timestamps;
// docs/microarchitecture.md, "Time in the SystemC model"). With SimContext::lockstep
// (VCD, timeline, or asked for) every stage also waits until SystemC time reaches its
// own before each step, and each FIFO transfer is checked against SystemC's time: then
// the state signals and recorders see time pass in order, as in a clocked model.
// The VCD state signal changes only at these calls, and so do the two optional recorders
// (null unless asked for; one branch each when off): the timeline's state track
// (sc/timeline.h) and the per-tile heat (sc/tile_heat.h).
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

#include <systemc>

#include "sc/link.h"
#include "sc/model_error.h"
#include "sc/sim_context.h"
#include "config/timing_params.h"
#include "sc/tile_heat.h"
#include "sc/timeline.h"
#include "timing/stage_table.h"

namespace rastsim::sc {

enum class StageState { Starved = 0, Busy = 1, Stalled = 2 };

struct StageStats {
  uint64_t busy = 0, stalled = 0, starved = 0;  // cycles
  uint64_t transactions_in = 0, transactions_out = 0;
  // A reading stage's transactions are its reads; a source stage's (command fetch) run
  // from its first busy cycle to its first write, however many outputs it writes (a 2D
  // command goes to the 2D front end and, as a marker, down the triangle path).
  uint64_t transactions() const { return transactions_in ? transactions_in : source_transactions; }
  uint64_t source_transactions = 0;
};

// Every transaction carries either a state command (viewport, scissor, clear) or work.
// State commands travel in program order with the primitives, so a clear reaches the
// ROP after every fragment of the triangles before it and before those after it.
template <class W>
struct Item {
  CommandPtr state;
  W work{};
};

class Stage : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Stage);
  // `id` is the stage's row of timing/stage_table.h; its stall stream offsets the stall seed.
  Stage(sc_core::sc_module_name name, SimContext& ctx, StageId id) : Stage(name, ctx, stage_info(id).stall_stream) {}
  // A stage outside the table (the binner, sc/binning.h) with a stall stream of its own.
  Stage(sc_core::sc_module_name name, SimContext& ctx, int stall_stream)
      : sc_module(name), ctx_(ctx), rng_(ctx.stall_seed * 0x9e3779b97f4a7c15ull + uint64_t(stall_stream)),
        state_("state", int(StageState::Starved)) {
    SC_THREAD(thread);
  }

  const StageStats& stats() const { return stats_; }
  sc_core::sc_signal<int>& state_signal() { return state_; }
  // This stage's time, in cycles: the end of its last busy, write or read.
  uint64_t now() const { return now_; }
  // The time of the stage whose thread calls this (for messages raised on a stage's
  // thread, such as a streamed scene's parse error in command fetch), or SystemC's
  // time outside any stage (one cycle is 1 ns: SimContext::cycle).
  static uint64_t current_cycle() {
    const auto* s = dynamic_cast<const Stage*>(sc_core::sc_get_current_process_handle().get_parent_object());
    return s ? s->now_ : uint64_t(sc_core::sc_time_stamp() / sc_core::sc_time(1, sc_core::SC_NS));
  }
  // At the end of the run (cycle `end`): the idle time since the stage last blocked is
  // starved time.
  void finish(uint64_t end) {
    end_span(idle_since_);
    if (end > idle_since_) {
      stats_.starved += end - idle_since_;
      record(StageState::Starved, idle_since_, end);
    }
    idle_since_ = end;
  }
  // Recorders (before sc_start): the stage's timeline track and tile heat, or null.
  void set_timeline(StateTrack* t) { track_ = t; }
  void set_heat(TileHeat* h) { heat_ = h; }
  void set_spans(std::vector<Span>* s) { spans_ = s; }

 protected:
  virtual void body() = 0;

  template <class P>
  P read(Link<P>& in, bool new_transaction = true) {
    set_state(StageState::Starved);
    if (new_transaction) end_span(now_);
    uint64_t left = 0;
    Tx<P> t = in.read(now_, left);
    check_lockstep(in.name(), "read", left);
    now_ = std::max(left, t.ready);  // starved until the transaction is ready
    sync();
    stats_.starved += now_ - idle_since_;
    record(StageState::Starved, idle_since_, now_);
    idle_since_ = now_;  // a second read in a row counts from here
    if (!new_transaction) return std::move(t.payload);
    ++stats_.transactions_in;
    begin_span();
    return std::move(t.payload);
  }

  void busy(uint64_t cycles) {
    if (cycles == 0) return;
    if (stats_.transactions_in == 0) {  // a source stage (command fetch)
      if (!source_open_) ++stats_.source_transactions;
      source_open_ = true;
      begin_span();
    }
    set_state(StageState::Busy);
    const uint64_t t0 = now_;
    now_ += cycles;
    sync();
    stats_.busy += cycles;
    record(StageState::Busy, t0, now_);
    if (heat_) heat_->charge(heat_tile_, cycles);
    idle_since_ = now_;
  }

  // Waits without work until cycle t (an interlock holding the transaction it read at its
  // input): starved, as while waiting to read.
  void starve_until(uint64_t t) {
    if (t <= now_) return;
    set_state(StageState::Starved);
    stats_.starved += t - idle_since_;
    record(StageState::Starved, idle_since_, t);
    now_ = t;
    sync();
    idle_since_ = now_;
  }

  // Writes one transaction; the reader may start on it `extra_latency` cycles from now.
  template <class P>
  void write(Link<P>& out, P payload, uint64_t extra_latency = 0) {
    const uint64_t t0 = now_;
    set_state(StageState::Stalled);
    if (ctx_.stall_probability > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < ctx_.stall_probability) {
      now_ += uint64_t(std::uniform_int_distribution<int>(1, ctx_.stall_max_cycles)(rng_));
      sync();
    }
    now_ = out.write(std::move(payload), now_, t0 + extra_latency);
    check_lockstep(out.name(), "write", now_);
    stats_.stalled += now_ - t0;
    record(StageState::Stalled, t0, now_);
    ++stats_.transactions_out;
    idle_since_ = now_;
    if (stats_.transactions_in == 0) {  // a source stage's transaction ends with its write
      source_open_ = false;
      end_span(idle_since_);
    }
  }

  // A state command takes one cycle of a stage's issue slot and then, like any other
  // transaction, the stage's pipeline latency (`extra_latency`, as for its work items):
  // in hardware it travels through the same pipeline registers. Returns true when `in`
  // was one.
  template <class In, class Out>
  bool pass_state(const Item<In>& in, Link<Item<Out>>& out, uint64_t extra_latency = 0) {
    if (!in.state) return false;
    attribute_to_no_tile();
    busy(TimingParams::state_pass_cycles());
    write(out, Item<Out>{in.state, {}}, extra_latency);
    return true;
  }

  // The tile the following busy() cycles are charged to (--heatmap): pixel (x, y)'s,
  // or none (state commands and other work of no tile).
  void attribute_to(int x, int y) {
    if (heat_) heat_tile_ = heat_->tile_of(x, y);
  }
  void attribute_to_no_tile() { heat_tile_ = -1; }

  SimContext& ctx_;

 private:
  // Lock-step only: SystemC time catches up with the stage's (the waits a clocked model
  // would make, so signals and recorders see time in order).
  void sync() {
    if (!ctx_.lockstep) return;
    const uint64_t sc_now = ctx_.to_cycles(sc_core::sc_time_stamp());
    if (now_ > sc_now) wait(double(now_ - sc_now) * ctx_.cycle);
  }
  // Lock-step only: a FIFO transfer the Link timed at `cycle` must happen at that
  // SystemC time, when the process blocked on it resumes: the timestamps agree with
  // SystemC's own scheduling, or the model is wrong.
  void check_lockstep(const char* link, const char* what, uint64_t cycle) const {
    if (ctx_.lockstep) check_lockstep_at(link, what, cycle);  // one inlined branch when off
  }
  [[gnu::noinline]] void check_lockstep_at(const char* link, const char* what, uint64_t cycle) const {
    const uint64_t sc_now = ctx_.to_cycles(sc_core::sc_time_stamp());
    if (cycle != sc_now)
      throw ModelError(std::string(name()) + ": " + what + " on " + link + " timed at cycle " + std::to_string(cycle) +
                       " but SystemC is at cycle " + std::to_string(sc_now));
  }
  void record(StageState s, uint64_t t0, uint64_t t1) {
    if (track_) track_->add(uint8_t(s), t0, t1);
  }
  // --trace-diff's transaction spans (null: off; one branch when off).
  void begin_span() {
    if (!spans_ || span_open_) return;
    span_open_ = true;
    spans_->push_back(Span{now_, 0});
  }
  void end_span(uint64_t t) {
    if (!spans_ || !span_open_) return;
    span_open_ = false;
    spans_->back().t1 = t;
  }
  void thread() {
    try {
      body();
    } catch (...) {
      ctx_.fail(std::current_exception());
    }
  }
  void set_state(StageState s) {
    if (!ctx_.tracing) return;
    sync();
    state_.write(int(s));
  }

  std::mt19937_64 rng_;
  sc_core::sc_signal<int> state_;
  StageStats stats_;
  uint64_t now_ = 0;         // this stage's time (cycles)
  uint64_t idle_since_ = 0;  // end of the last busy/write (cycles)
  StateTrack* track_ = nullptr;  // --timeline: this stage's intervals
  TileHeat* heat_ = nullptr;     // --heatmap: this stage's busy cycles per tile
  int heat_tile_ = -1;           // tile the next busy() is charged to (-1: none)
  std::vector<Span>* spans_ = nullptr;  // --trace-diff: this stage's transactions
  bool span_open_ = false;              // the last span has no end yet
  bool source_open_ = false;            // a source stage's transaction is in progress
};

}  // namespace rastsim::sc
