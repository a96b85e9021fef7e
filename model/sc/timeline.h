// SPDX-License-Identifier: Apache-2.0
// Timeline: where the cycles go, as a Chrome/Perfetto trace-event JSON (docs/timeline.md).
//
// - One StateTrack per stage records the busy/stalled/starved intervals Stage::read(),
//   busy() and write() account (sc/stage.h), merging an interval into the previous one
//   when both have the same state and touch; one CounterTrack per FIFO records its
//   occupancy (transactions) each time it changes (sc/link.h).
// - Stages and FIFOs hold a null track pointer unless --timeline is given, so recording
//   costs one branch per call when off.
// - write_trace_json() writes "X" events (ts/dur in cycles: 1 us in the viewer = 1
//   cycle), "C" counter events and "M" thread/process-name events. When the merged
//   intervals exceed `max_events`, it quantizes to R-cycle buckets (R a power of two):
//   each bucket becomes at most three events, busy, stalled, starved in that order with
//   the bucket's exact totals (so per-stage sums stay exact), merged with neighbours of
//   the same state; a FIFO's counter shows each bucket's peak occupancy. Bound per
//   track: 3 * ceil(cycles / R) + 1 events.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace rastsim::sc {

struct Interval {
  uint64_t t0 = 0, t1 = 0;  // cycles, [t0, t1)
  uint8_t state = 0;        // StageState: 0 starved, 1 busy, 2 stalled
};

class StateTrack {
 public:
  explicit StateTrack(std::string name) : name_(std::move(name)) {}
  // Adds [t0, t1) in `state`; empty intervals are dropped, touching same-state ones merged.
  void add(uint8_t state, uint64_t t0, uint64_t t1) {
    if (t1 <= t0) return;
    if (!iv_.empty() && iv_.back().state == state && iv_.back().t1 == t0) {
      iv_.back().t1 = t1;
      return;
    }
    iv_.push_back({t0, t1, state});
  }
  const std::string& name() const { return name_; }
  const std::vector<Interval>& intervals() const { return iv_; }

 private:
  std::string name_;
  std::vector<Interval> iv_;  // in time order, non-overlapping
};

// One transaction of a stage (rastsim cosim --trace-diff): cycles [t0, t1) from the
// cycle the stage starts on it (its read returns; a source stage: its first busy cycle)
// to the end of its work for it (the stage's next read; a source stage: its write).
struct Span {
  uint64_t t0 = 0, t1 = 0;
};

struct CounterSample {
  uint64_t t = 0;  // cycles
  int value = 0;   // transactions in the FIFO from t on
};

class CounterTrack {
 public:
  CounterTrack(std::string name, int depth) : name_(std::move(name)), depth_(depth) {}
  // Occupancy `value` from cycle t on; a later change at the same cycle replaces it.
  void set(uint64_t t, int value) {
    if (!s_.empty() && s_.back().t == t) {
      s_.back().value = value;
      if (s_.size() > 1 && s_[s_.size() - 2].value == value) s_.pop_back();
      return;
    }
    if (!s_.empty() && s_.back().value == value) return;
    s_.push_back({t, value});
  }
  const std::string& name() const { return name_; }
  int depth() const { return depth_; }
  const std::vector<CounterSample>& samples() const { return s_; }

 private:
  std::string name_;
  int depth_;
  std::vector<CounterSample> s_;
};

struct TimelineWriteStats {
  uint64_t events = 0, bytes = 0;
  uint64_t resolution_cycles = 1;  // 1 = every merged interval as recorded
};

class Timeline {
 public:
  // Tracks live as long as the Timeline (deque: stable addresses for the stages).
  StateTrack& add_stage(const std::string& name) { return stages_.emplace_back(name); }
  CounterTrack& add_fifo(const std::string& name, int depth) { return fifos_.emplace_back(name, depth); }
  const std::deque<StateTrack>& stages() const { return stages_; }
  const std::deque<CounterTrack>& fifos() const { return fifos_; }

  // Writes the trace of a run of `cycles` cycles. Throws std::runtime_error naming the
  // file when it cannot be written.
  TimelineWriteStats write_trace_json(const std::string& path, uint64_t cycles, uint64_t max_events) const;

 private:
  std::deque<StateTrack> stages_;
  std::deque<CounterTrack> fifos_;
};

}  // namespace rastsim::sc
