// SPDX-License-Identifier: Apache-2.0
// Stage: the base of every pipeline stage module. One SC_THREAD runs the stage's body();
// the helpers below are the only places time passes, and they account it:
//
// - read():  blocks on the input FIFO, then until the transaction is ready -> starved
//            (read(in, false): a further input of the transaction in progress, as the
//            2D engine's grant or the ROP's 2D done: starved, no new transaction)
// - busy(n): one wait of n cycles for one transaction's work                -> busy
// - write(): blocks on a full output FIFO (plus injected stalls)           -> stalled
//
// Every cycle of a stage is exactly one of busy, stalled or starved, so the three add
// up to the simulated cycle count. The VCD state signal changes only at these calls, and
// so do the two optional recorders (null unless asked for; one branch each when off):
// the timeline's state track (sc/timeline.h) and the per-tile heat (sc/tile_heat.h).
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include <systemc>

#include "sc/link.h"
#include "sc/sim_context.h"
#include "config/timing_params.h"
#include "sc/tile_heat.h"
#include "sc/timeline.h"

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
  Stage(sc_core::sc_module_name name, SimContext& ctx, int index)
      : sc_module(name), ctx_(ctx), rng_(ctx.stall_seed * 0x9e3779b97f4a7c15ull + uint64_t(index)),
        state_("state", int(StageState::Starved)) {
    SC_THREAD(thread);
  }

  const StageStats& stats() const { return stats_; }
  sc_core::sc_signal<int>& state_signal() { return state_; }
  // At the end of the run: the idle time since the stage last blocked is starved time.
  void finish(const sc_core::sc_time& end) {
    end_span(idle_since_);
    if (end > idle_since_) {
      stats_.starved += ctx_.to_cycles(end - idle_since_);
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
    if (new_transaction) end_span(sc_core::sc_time_stamp());
    Tx<P> t = in.read();
    if (t.ready > sc_core::sc_time_stamp()) wait(t.ready - sc_core::sc_time_stamp());
    stats_.starved += ctx_.to_cycles(sc_core::sc_time_stamp() - idle_since_);
    record(StageState::Starved, idle_since_, sc_core::sc_time_stamp());
    idle_since_ = sc_core::sc_time_stamp();  // a second read in a row counts from here
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
    const sc_core::sc_time t0 = sc_core::sc_time_stamp();
    wait(double(cycles) * ctx_.cycle);
    stats_.busy += cycles;
    record(StageState::Busy, t0, sc_core::sc_time_stamp());
    if (heat_) heat_->charge(heat_tile_, cycles);
    idle_since_ = sc_core::sc_time_stamp();
  }

  // Writes one transaction; the reader may start on it `extra_latency` cycles from now.
  template <class P>
  void write(Link<P>& out, P payload, uint64_t extra_latency = 0) {
    const sc_core::sc_time t0 = sc_core::sc_time_stamp();
    set_state(StageState::Stalled);
    if (ctx_.stall_probability > 0 && std::uniform_real_distribution<double>(0, 1)(rng_) < ctx_.stall_probability)
      wait(double(std::uniform_int_distribution<int>(1, ctx_.stall_max_cycles)(rng_)) * ctx_.cycle);
    out.write(std::move(payload), t0 + double(extra_latency) * ctx_.cycle);
    stats_.stalled += ctx_.to_cycles(sc_core::sc_time_stamp() - t0);
    record(StageState::Stalled, t0, sc_core::sc_time_stamp());
    ++stats_.transactions_out;
    idle_since_ = sc_core::sc_time_stamp();
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
  void record(StageState s, const sc_core::sc_time& t0, const sc_core::sc_time& t1) {
    if (track_) track_->add(uint8_t(s), ctx_.to_cycles(t0), ctx_.to_cycles(t1));
  }
  // --trace-diff's transaction spans (null: off; one branch when off).
  void begin_span() {
    if (!spans_ || span_open_) return;
    span_open_ = true;
    spans_->push_back(Span{ctx_.to_cycles(sc_core::sc_time_stamp()), 0});
  }
  void end_span(const sc_core::sc_time& t) {
    if (!spans_ || !span_open_) return;
    span_open_ = false;
    spans_->back().t1 = ctx_.to_cycles(t);
  }
  void thread() {
    try {
      body();
    } catch (...) {
      ctx_.fail(std::current_exception());
    }
  }
  void set_state(StageState s) {
    if (ctx_.tracing) state_.write(int(s));
  }

  std::mt19937_64 rng_;
  sc_core::sc_signal<int> state_;
  StageStats stats_;
  sc_core::sc_time idle_since_ = sc_core::SC_ZERO_TIME;  // end of the last busy/write
  StateTrack* track_ = nullptr;  // --timeline: this stage's intervals
  TileHeat* heat_ = nullptr;     // --heatmap: this stage's busy cycles per tile
  int heat_tile_ = -1;           // tile the next busy() is charged to (-1: none)
  std::vector<Span>* spans_ = nullptr;  // --trace-diff: this stage's transactions
  bool span_open_ = false;              // the last span has no end yet
  bool source_open_ = false;            // a source stage's transaction is in progress
};

}  // namespace rastsim::sc
