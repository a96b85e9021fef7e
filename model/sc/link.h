// SPDX-License-Identifier: Apache-2.0
// Link<P>: the bounded FIFO between two stages, a timestamped channel, with
//
// - backpressure: depth from the config (fifo.*_depth). Transaction k takes the slot
//   transaction k - depth held, so it enters the FIFO at the later of the cycle its
//   writer offers it and the cycle the reader took k - depth out (write());
// - a ready time on every transaction, so a stage can model a pipeline latency longer
//   than its initiation interval without a second process (the reader starts on it at
//   the latest of its own cycle, the cycle it entered and its ready cycle; Stage::read);
// - an order check: the writer numbers transactions, the reader checks it receives
//   0, 1, 2, ... (a lost or reordered transaction is an error, never silent);
// - an occupancy signal for the VCD and an optional timeline counter (sc/timeline.h),
//   both writes - reads, changed when a transaction enters or leaves (so it never
//   exceeds the depth).
//
// Why timestamps (docs/microarchitecture.md, "Time in the SystemC model"): every cycle a
// transaction enters or leaves is computed from the two stages' own cycle counts, never
// read from SystemC's clock, so a stage may run ahead of SystemC time (temporal
// decoupling) and still get exactly the cycles of a FIFO that advanced with the clock.
// SystemC only orders the processes: a reader of an empty FIFO or a writer of a full
// one suspends on an event until the other side has acted (immediate notification, no
// delta cycle), as an sc_fifo would, but no process waits for time to pass unless the
// run is in lock-step (SimContext::lockstep).
//
// Wake-ups: a writer suspended on a full FIFO resumes once its reader has emptied it,
// not at the first free slot (unless in lock-step, where every transfer must happen at
// its own SystemC time, or with memory requests in time order, where a writer woken late
// would make its requests after SystemC time passed their cycles; sc/sim_context.h).
// Otherwise which process runs when never changes a timestamp (they come from the two
// stages' cycle counts and the slots' freed cycles only), so this changes no result; it
// lets a writer refill the whole FIFO in one go instead of a slot at a time, which on
// small triangles woke every stage above the busiest one once per few tiles (a quarter
// of the process switches on the mesh scene). It cannot deadlock: a reader stops short
// of emptying its input only while its own output is full, which the stages below drain
// (the ROP, at the bottom, reads its FIFO until empty); the 2D engine's inputs were
// written before the markers the ROP waits on (sc/command_fetch.h).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include "sc/model_error.h"
#include "sc/timeline.h"

namespace rastsim::sc {

template <class P>
struct Tx {
  P payload;
  uint64_t ready = 0;    // cycle: earliest the reader may start on it
  uint64_t entered = 0;  // cycle: when it entered the FIFO (a slot was free)
  uint64_t seq = 0;      // position in this FIFO's stream
};

template <class P>
class Link : public sc_core::sc_module {
 public:
  // tracing: update the occupancy signal; wake_at_free_slot: wake a waiting writer at the
  // first free slot (see above; read at each wake, as it may be set during the run:
  // SimContext::wake_writers_at_free_slot).
  Link(sc_core::sc_module_name name, int depth, bool tracing, const bool& wake_at_free_slot)
      : sc_module(name), depth_(depth), slots_(size_t(depth)), freed_(size_t(depth), 0),
        occupancy_("occupancy", 0), tracing_(tracing), wake_at_free_slot_(wake_at_free_slot) {
    if (depth < 1) throw ModelError(std::string(this->name()) + ": FIFO depth " + std::to_string(depth) + " < 1");
  }

  // Writes one transaction offered at cycle `at`, which its reader may start on from
  // cycle `ready`; suspends the calling process while the FIFO is full (every slot
  // written and not yet read). Returns the cycle it entered: max(at, the cycle its slot
  // was freed).
  uint64_t write(P payload, uint64_t at, uint64_t ready) {
    while (writes_ - reads_ >= uint64_t(depth_)) {
      writer_waiting_ = true;
      sc_core::wait(read_event_);
    }
    const size_t slot = write_slot_;
    write_slot_ = next_slot(slot);
    const uint64_t entered = std::max(at, freed_[slot]);
    slots_[slot] = Tx<P>{std::move(payload), ready, entered, writes_};
    ++writes_;
    if (reader_waiting_) {
      reader_waiting_ = false;
      write_event_.notify();  // immediate: the reader runs in this evaluation phase
    }
    changed(entered);
    return entered;
  }
  // Reads the next transaction at cycle `at`; suspends the calling process while the
  // FIFO is empty. Sets `left` to the cycle it leaves the FIFO (max(at, entered)), which
  // frees its slot for the transaction `depth` later.
  Tx<P> read(uint64_t at, uint64_t& left) {
    while (writes_ == reads_) {
      reader_waiting_ = true;
      sc_core::wait(write_event_);
    }
    const size_t slot = read_slot_;
    read_slot_ = next_slot(slot);
    Tx<P> t = std::move(slots_[slot]);
    check_order(name(), reads_, t.seq);
    left = std::max(at, t.entered);
    freed_[slot] = left;
    ++reads_;
    if (writer_waiting_ && (writes_ == reads_ || wake_at_free_slot_)) {
      writer_waiting_ = false;
      read_event_.notify();
    }
    changed(left);
    return t;
  }
  // --timeline: this FIFO's occupancy track, or null (before sc_start). It needs the
  // changes in time order: a lock-step run (SimContext::lockstep).
  void set_timeline(CounterTrack* c) { counter_ = c; }

  int depth() const { return depth_; }
  uint64_t writes() const { return writes_; }
  uint64_t reads() const { return reads_; }
  sc_core::sc_signal<int, sc_core::SC_UNCHECKED_WRITERS>& occupancy() { return occupancy_; }

 private:
  void changed(uint64_t cycle) {
    if (tracing_) occupancy_.write(int(writes_ - reads_));
    if (counter_) counter_->set(cycle, int(writes_ - reads_));
  }
  int depth_;
  // The slot after `slot` in the ring (a compare, not a 64-bit division a transfer).
  size_t next_slot(size_t slot) const { return slot + 1 == size_t(depth_) ? 0 : slot + 1; }
  std::vector<Tx<P>> slots_;     // ring: transaction k in slot k % depth
  size_t write_slot_ = 0, read_slot_ = 0;  // writes_ % depth, reads_ % depth
  std::vector<uint64_t> freed_;  // per slot: the cycle its last transaction left (0: never used)
  sc_core::sc_event write_event_, read_event_;
  bool reader_waiting_ = false, writer_waiting_ = false;
  sc_core::sc_signal<int, sc_core::SC_UNCHECKED_WRITERS> occupancy_;  // both stages write it, the same count: the last write of a delta stands
  bool tracing_;
  const bool& wake_at_free_slot_;  // else a waiting writer resumes when the FIFO is empty
  uint64_t writes_ = 0, reads_ = 0;
  CounterTrack* counter_ = nullptr;
};

}  // namespace rastsim::sc
