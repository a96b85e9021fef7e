// SPDX-License-Identifier: Apache-2.0
// Hi-Z's interlock in the timed model (docs/depth-culling.md "The interlock"), the same
// rule as rast_top's (rtl/rast_hiz_inflight.sv): coarse raster tests a tile only once no
// tile (or state item) it sent earlier that touches the tile's blocks is still in flight
// to the ROP, so a hardware table updated by the ROP's depth writes would hold exactly
// what the functional-first HizTracker tests against. The decisions stay HizTracker's;
// the interlock only times them.
//
// - Coarse raster records every tile it sends (its footprint's blocks) and every state
//   item (every block: a depth clear reaches the table at the ROP), in send order.
// - An entry ends at the cycle fine raster drops its tile (no covered pixel; fine raster
//   takes entries in send order) or the cycle the ROP finishes it (the end of its busy
//   cycles: the ROP takes the oldest entry not yet ended, in order).
// - free_at(fp): the first cycle at which every earlier entry touching fp's blocks has
//   ended. The stages run decoupled (sc/stage.h), so an end may not be known yet when
//   coarse raster asks: it then waits (SystemC) for the ROP or fine raster to record it;
//   the tile in question is already downstream, so the wait always ends.
// - depth.hiz_sync = lagged: coarse raster never holds a tile for its blocks; it asks
//   busy_at only to know whether they are busy at the test (an accept then waits for
//   nothing: the tile is drawn), ended_by to time the lagged table's updates at each
//   entry's end, and holds a tile only while a state item (a depth clear) is in flight.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <deque>
#include <limits>

#include <systemc>

#include "ref/coarse_raster.h"
#include "sc/sim_context.h"

namespace rastsim::sc {

class HizInterlock {
 public:
  HizInterlock(int block, const SimContext& ctx) : log2b_(std::countr_zero(unsigned(block))), ctx_(ctx) {}

  // Coarse raster sends a tile of footprint fp / a state item (every block); returns the
  // entry's number (send order, from 0: end_of's argument).
  uint64_t sent(const PixelRect& fp) {
    q_.push_back({blocks_of(fp), false, kOpen});
    return base_ + q_.size() - 1;
  }
  uint64_t sent_state() {
    q_.push_back({{}, true, kOpen});
    return base_ + q_.size() - 1;
  }
  // Fine raster finished its next entry at cycle t: dropped (ends it) or passed on.
  void fine(bool dropped, uint64_t t) {
    if (dropped) end(at(fine_), t);
    ++fine_;
  }
  // The ROP finished its oldest entry not yet ended, at cycle t (its busy's end).
  void rop_end(uint64_t t) {
    for (uint64_t i = base_; i < base_ + q_.size(); ++i)
      if (at(i).end == kOpen) return end(at(i), t);
  }
  // The first cycle from which fp's blocks have nothing in flight; entries that ended
  // before `now` (the caller's time, which only grows) are forgotten.
  uint64_t free_at(const PixelRect& fp, uint64_t now) {
    forget(now);
    const Blocks b = blocks_of(fp);
    uint64_t t = 0;
    for (size_t i = 0; i < q_.size(); ++i) {
      if (!touches(q_[i], b)) continue;
      while (q_[i].end == kOpen) sc_core::wait(ended_);  // decoupled: not recorded yet
      t = std::max(t, q_[i].end);
    }
    return t;
  }
  // depth.hiz_sync = lagged: whether an entry touching fp's blocks has not ended by cycle
  // t (free_at(fp, now) > t, without waiting for ends after t: see ended_by).
  bool busy_at(const PixelRect& fp, uint64_t now, uint64_t t) {
    forget(now);
    const Blocks b = blocks_of(fp);
    for (size_t i = 0; i < q_.size(); ++i)
      if (touches(q_[i], b) && !ended_by(base_ + i, t)) return true;
    return false;
  }
  // Whether entry i ended by cycle t, decided by SystemC time t: every end e is recorded by
  // SystemC time e - 1 (the ROP's after its busy, at e - 1; fine raster's drop before its
  // busy), the stages being at or ahead of SystemC time, decoupled or in lock-step. Not
  // recorded when SystemC time reaches t, it is later. Coarse raster, at or before t,
  // waits no later than t, so the test's spilled reads at t still enter the DRAM in time
  // order (waiting for the end itself, a decoupled run made them late and differed from a
  // lock-step one, which waited to t + 1).
  bool ended_by(uint64_t i, uint64_t t) {
    if (i < base_) return true;  // forgotten: ended by coarse raster's time
    while (at(i).end == kOpen) {
      const uint64_t sc_now = ctx_.to_cycles(sc_core::sc_time_stamp());
      if (sc_now >= t) return false;
      sc_core::wait(double(t - sc_now) * ctx_.cycle, ended_);
    }
    return at(i).end <= t;
  }
  // The first cycle from which no state item is in flight (depth.hiz_sync = lagged: a depth
  // clear in flight would make every stale bound unsafe). Call after free_at or alone.
  uint64_t state_free_at() {
    uint64_t t = 0;
    for (size_t i = 0; i < q_.size(); ++i) {
      if (!q_[i].all) continue;
      while (q_[i].end == kOpen) sc_core::wait(ended_);
      t = std::max(t, q_[i].end);
    }
    return t;
  }

 private:
  static constexpr uint64_t kOpen = std::numeric_limits<uint64_t>::max();
  struct Blocks {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive block range
  };
  struct Entry {
    Blocks b;
    bool all = false;  // a state item: every block
    uint64_t end = kOpen;
  };
  Entry& at(uint64_t i) { return q_[size_t(i - base_)]; }
  Blocks blocks_of(const PixelRect& fp) const {
    return {fp.x0 >> log2b_, fp.y0 >> log2b_, (fp.x1 - 1) >> log2b_, (fp.y1 - 1) >> log2b_};
  }
  static bool touches(const Entry& e, const Blocks& b) {
    return e.all || !(e.b.x1 < b.x0 || e.b.x0 > b.x1 || e.b.y1 < b.y0 || e.b.y0 > b.y1);
  }
  // Entries that ended before `now` (the caller's time, which only grows) are forgotten,
  // only from the front. One that ends at `now` is kept: early Z's batch enters the cycle
  // after its end (free_at + 1), and whether the ROP had recorded it when the caller asks
  // depends on which process SystemC ran first (a decoupled and a lock-step run differed).
  void forget(uint64_t now) {
    while (!q_.empty() && q_.front().end < now && base_ < fine_) {
      q_.pop_front();
      ++base_;
    }
  }
  void end(Entry& e, uint64_t t) {
    e.end = t;
    ended_.notify(sc_core::SC_ZERO_TIME);
  }
  int log2b_;
  const SimContext& ctx_;
  std::deque<Entry> q_;  // entries base_ .. base_ + size - 1, in send order
  uint64_t base_ = 0, fine_ = 0;  // the first entry held; fine raster's next
  sc_core::sc_event ended_;
};

}  // namespace rastsim::sc
