// SPDX-License-Identifier: Apache-2.0
// Link<P>: the bounded FIFO between two stages (an sc_fifo of transactions), with
//
// - backpressure: depth from the config (fifo.*_depth), a full FIFO blocks its writer;
// - a ready time on every transaction, so a stage can model a pipeline latency longer
//   than its initiation interval without a second process (the reader waits until the
//   transaction is ready; see Stage::read);
// - an order check: the writer numbers transactions, the reader checks it receives
//   0, 1, 2, ... (a lost or reordered transaction is an error, never silent);
// - an occupancy signal for the VCD, updated only when a transaction enters or leaves;
// - an optional timeline counter (sc/timeline.h) of the same occupancy, counted as
//   writes - reads when a write or read returns (a slot is taken when write() returns
//   and freed when read() returns, so it never exceeds the depth).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include <systemc>

#include "sc/model_error.h"
#include "sc/timeline.h"

namespace rastsim::sc {

template <class P>
struct Tx {
  P payload;
  sc_core::sc_time ready;  // earliest time the reader may start on it
  uint64_t seq = 0;        // position in this FIFO's stream
};
// sc_fifo needs operator<< for its element type (sc_fifo::print).
template <class P>
std::ostream& operator<<(std::ostream& os, const Tx<P>& t) {
  return os << "tx#" << t.seq;
}

template <class P>
class Link : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Link);
  Link(sc_core::sc_module_name name, int depth, bool tracing)
      : sc_module(name), depth_(depth), fifo_("fifo", depth), occupancy_("occupancy", 0) {
    if (tracing) {
      SC_METHOD(track);
      sensitive << fifo_.data_written_event() << fifo_.data_read_event();
      dont_initialize();
    }
  }

  void write(P payload, const sc_core::sc_time& ready) {
    fifo_.write(Tx<P>{std::move(payload), ready, writes_++});
    if (counter_) record();
  }
  Tx<P> read() {
    Tx<P> t = fifo_.read();
    check_order(name(), reads_, t.seq);
    ++reads_;
    if (counter_) record();
    return t;
  }
  // --timeline: this FIFO's occupancy track, or null (before sc_start).
  void set_timeline(CounterTrack* c) { counter_ = c; }

  int depth() const { return depth_; }
  uint64_t writes() const { return writes_; }
  uint64_t reads() const { return reads_; }
  sc_core::sc_signal<int>& occupancy() { return occupancy_; }

 private:
  void track() { occupancy_.write(fifo_.num_available()); }
  void record() {  // at the current time, in cycles (one cycle is 1 ns: SimContext::cycle)
    const sc_core::sc_time& now = sc_core::sc_time_stamp();
    counter_->set(uint64_t(now.value() / sc_core::sc_time(1, sc_core::SC_NS).value()), int(writes_ - reads_));
  }
  int depth_;
  sc_core::sc_fifo<Tx<P>> fifo_;
  sc_core::sc_signal<int> occupancy_;
  uint64_t writes_ = 0, reads_ = 0;
  CounterTrack* counter_ = nullptr;
};

}  // namespace rastsim::sc
