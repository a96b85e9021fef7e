// SPDX-License-Identifier: Apache-2.0
#include "sc/timeline.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"

namespace rastsim::sc {

namespace {

constexpr std::array<const char*, 3> kStateName = {"starved", "busy", "stalled"};  // by StageState

void push_merged(std::vector<Interval>& out, uint8_t state, uint64_t t0, uint64_t t1) {
  if (t1 <= t0) return;
  if (!out.empty() && out.back().state == state && out.back().t1 == t0) {
    out.back().t1 = t1;
    return;
  }
  out.push_back({t0, t1, state});
}

// R-cycle buckets: a run of whole buckets in one state stays one interval; a bucket
// holding several states becomes its busy, stalled and starved totals laid end to end
// from the bucket's start. Totals per state are unchanged; nothing overlaps.
std::vector<Interval> quantize(const std::vector<Interval>& iv, uint64_t r) {
  std::vector<Interval> out;
  uint64_t bucket = UINT64_MAX;  // bucket being summed (none yet)
  std::array<uint64_t, 3> total{};
  auto flush = [&] {
    if (bucket == UINT64_MAX) return;
    uint64_t t = bucket * r;
    for (uint8_t s : {uint8_t(1), uint8_t(2), uint8_t(0)}) {
      push_merged(out, s, t, t + total[s]);
      t += total[s];
    }
    total = {};
    bucket = UINT64_MAX;
  };
  for (const Interval& i : iv) {
    uint64_t a = i.t0;
    while (a < i.t1) {
      const uint64_t k = a / r, bucket_end = (k + 1) * r;
      if (a % r == 0 && i.t1 >= bucket_end) {  // whole buckets in this one state
        flush();
        const uint64_t whole_end = i.t1 - i.t1 % r;
        push_merged(out, i.state, a, whole_end);
        a = whole_end;
        continue;
      }
      if (k != bucket) {
        flush();
        bucket = k;
      }
      const uint64_t e = std::min(i.t1, bucket_end);
      total[i.state] += e - a;
      a = e;
    }
  }
  flush();
  return out;
}

// A FIFO's occupancy per R-cycle bucket: the bucket's peak (so a full FIFO still shows
// as full), then the value it was left at if the following buckets have no change.
std::vector<CounterSample> quantize(const std::vector<CounterSample>& s, uint64_t r) {
  std::vector<CounterSample> out;
  auto push = [&](uint64_t t, int v) {
    if (!out.empty() && out.back().value == v) return;
    out.push_back({t, v});
  };
  int cur = 0;  // every FIFO starts empty
  uint64_t last_bucket = UINT64_MAX;
  for (size_t i = 0; i < s.size();) {
    const uint64_t k = s[i].t / r;
    if (last_bucket != UINT64_MAX && k > last_bucket + 1) push((last_bucket + 1) * r, cur);
    int peak = cur;
    for (; i < s.size() && s[i].t / r == k; ++i) {
      peak = std::max(peak, s[i].value);
      cur = s[i].value;
    }
    push(k * r, peak);
    last_bucket = k;
  }
  if (last_bucket != UINT64_MAX) push((last_bucket + 1) * r, cur);
  return out;
}

}  // namespace

TimelineWriteStats Timeline::write_trace_json(const std::string& path, uint64_t cycles, uint64_t max_events) const {
  // Choose the resolution: 1 if the merged intervals fit, else the smallest power of two
  // whose buckets fit (or the one that makes the whole run one bucket).
  std::vector<std::vector<Interval>> iv;
  std::vector<std::vector<CounterSample>> cs;
  uint64_t r = 1;
  for (;;) {
    iv.clear();
    cs.clear();
    uint64_t n = fifos_.size();  // each FIFO's initial zero (below)
    for (const StateTrack& t : stages_) {
      iv.push_back(r == 1 ? t.intervals() : quantize(t.intervals(), r));
      n += iv.back().size();
    }
    for (const CounterTrack& f : fifos_) {
      cs.push_back(r == 1 ? f.samples() : quantize(f.samples(), r));
      n += cs.back().size();
    }
    if (n <= max_events || r >= cycles) break;
    r *= 2;
  }

  AtomicFile file(path);  // whole or not at all (util/atomic_file.h)
  std::ofstream& os = file.stream();
  TimelineWriteStats st;
  st.resolution_cycles = r;
  // ts and dur are in cycles. The format's unit is the microsecond, so 1 us in the
  // viewer is 1 core cycle (whatever clock.core_mhz says).
  os << "{\"otherData\":{\"time_unit\":\"1 us in the viewer = 1 core cycle\",\"cycles\":" << cycles
     << ",\"resolution_cycles\":" << r << "},\n\"traceEvents\":[\n";
  bool first = true;
  auto sep = [&] {
    if (!first) os << ",\n";
    first = false;
    ++st.events;
  };
  // Metadata: pid 1 holds one thread per stage (its state), pid 2 the FIFO counters.
  sep();
  os << R"J({"name":"process_name","ph":"M","pid":1,"args":{"name":"stages (busy/stalled/starved)"}})J";
  sep();
  os << R"J({"name":"process_name","ph":"M","pid":2,"args":{"name":"FIFOs (occupancy, transactions)"}})J";
  for (size_t i = 0; i < stages_.size(); ++i) {
    sep();
    os << R"({"name":"thread_name","ph":"M","pid":1,"tid":)" << i + 1 << R"(,"args":{"name":")"
       << stages_[i].name() << "\"}}";
    sep();  // keep pipeline order in the viewer
    os << R"({"name":"thread_sort_index","ph":"M","pid":1,"tid":)" << i + 1 << R"(,"args":{"sort_index":)" << i
       << "}}";
  }
  for (size_t i = 0; i < fifos_.size(); ++i) {
    // Counters live on the process; one thread per FIFO names it and records its depth.
    sep();
    os << R"({"name":"thread_name","ph":"M","pid":2,"tid":)" << i + 1 << R"(,"args":{"name":")"
       << fifos_[i].name() << " (depth " << fifos_[i].depth() << ")\"}}";
  }
  for (size_t i = 0; i < stages_.size(); ++i)
    for (const Interval& v : iv[i]) {
      sep();
      os << R"({"name":")" << kStateName[v.state] << R"(","ph":"X","pid":1,"tid":)" << i + 1 << ",\"ts\":" << v.t0
         << ",\"dur\":" << v.t1 - v.t0 << '}';
    }
  for (size_t i = 0; i < fifos_.size(); ++i) {
    // Every FIFO starts empty: say so at cycle 0, so an unused FIFO still gets its counter track.
    if (cs[i].empty() || cs[i].front().t > 0) cs[i].insert(cs[i].begin(), CounterSample{0, 0});
    for (const CounterSample& c : cs[i]) {
      sep();
      os << R"({"name":")" << fifos_[i].name() << R"(","ph":"C","pid":2,"tid":)" << i + 1 << ",\"ts\":" << c.t
         << R"(,"args":{"occupancy":)" << c.value << "}}";
    }
  }
  os << "\n]}\n";
  st.bytes = uint64_t(os.tellp());
  file.commit();
  return st;
}

}  // namespace rastsim::sc
