// SPDX-License-Identifier: Apache-2.0
// Stage: the base of every pipeline stage module. One SC_THREAD runs the stage's body();
// the helpers below are the only places time passes, and they account it:
//
// - read():  blocks on the input FIFO, then until the transaction is ready -> starved
// - busy(n): one wait of n cycles for one transaction's work                -> busy
// - write(): blocks on a full output FIFO (plus injected stalls)           -> stalled
//
// Every cycle of a stage is exactly one of busy, stalled or starved, so the three add
// up to the simulated cycle count. The VCD state signal changes only at these calls.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include <systemc>

#include "sc/link.h"
#include "sc/sim_context.h"
#include "config/timing_params.h"

namespace rastsim::sc {

enum class StageState { Starved = 0, Busy = 1, Stalled = 2 };

struct StageStats {
  uint64_t busy = 0, stalled = 0, starved = 0;  // cycles
  uint64_t transactions_in = 0, transactions_out = 0;
};

// Every transaction carries either a state command (viewport, scissor, clear) or work.
// State commands travel in program order with the primitives, so a clear reaches the
// ROP after every fragment of the triangles before it and before those after it.
template <class W>
struct Item {
  const Command* state = nullptr;
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
    if (end > idle_since_) stats_.starved += ctx_.to_cycles(end - idle_since_);
    idle_since_ = end;
  }

 protected:
  virtual void body() = 0;

  template <class P>
  P read(Link<P>& in) {
    set_state(StageState::Starved);
    Tx<P> t = in.read();
    if (t.ready > sc_core::sc_time_stamp()) wait(t.ready - sc_core::sc_time_stamp());
    stats_.starved += ctx_.to_cycles(sc_core::sc_time_stamp() - idle_since_);
    idle_since_ = sc_core::sc_time_stamp();  // a second read in a row counts from here
    ++stats_.transactions_in;
    return std::move(t.payload);
  }

  void busy(uint64_t cycles) {
    if (cycles == 0) return;
    set_state(StageState::Busy);
    wait(double(cycles) * ctx_.cycle);
    stats_.busy += cycles;
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
    ++stats_.transactions_out;
    idle_since_ = sc_core::sc_time_stamp();
  }

  // A state command takes one cycle of a stage's issue slot and then, like any other
  // transaction, the stage's pipeline latency (`extra_latency`, as for its work items):
  // in hardware it travels through the same pipeline registers. Returns true when `in`
  // was one.
  template <class In, class Out>
  bool pass_state(const Item<In>& in, Link<Item<Out>>& out, uint64_t extra_latency = 0) {
    if (!in.state) return false;
    busy(TimingParams::state_pass_cycles());
    write(out, Item<Out>{in.state, {}}, extra_latency);
    return true;
  }

  SimContext& ctx_;

 private:
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
};

}  // namespace rastsim::sc
