// SPDX-License-Identifier: Apache-2.0
#include "fidelity/frame_sampled.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <numeric>
#include <span>
#include <stdexcept>

#include "fidelity/functional_pass.h"
#include "fidelity/run_child.h"
#include "fidelity/student_t.h"
#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "sc/raster_pipeline.h"

namespace rastsim::fidelity {

namespace {

// The frames of `rest` (sorted by x) cut into n runs of equal counts; each run's member
// nearest its mean x (ties: the lower frame) is chosen.
void choose_clusters(FramePlan& p, const std::vector<size_t>& rest, size_t n) {
  const size_t M = rest.size();
  for (size_t c = 0; c < n; ++c) {
    const size_t lo = c * M / n, hi = (c + 1) * M / n;  // members rest[lo, hi): equal counts
    double mean = 0;
    for (size_t i = lo; i < hi; ++i) mean += p.x[rest[i]] / double(hi - lo);
    size_t rep = rest[lo];
    for (size_t i = lo; i < hi; ++i) {
      p.cluster[rest[i]] = int(p.clusters);
      const double d = std::abs(p.x[rest[i]] - mean), dr = std::abs(p.x[rep] - mean);
      if (d < dr || (d == dr && rest[i] < rep)) rep = rest[i];
    }
    p.chosen[rep] = true;
    ++p.clusters;
  }
}

// A frame's stratum: its busiest stage (ties: the earlier stage) and the set of stages
// with any work (a frame with a 2D fill, a texture or clip-space input is another kind
// of frame even where the same stage is busiest: on embedded the torus frames with a
// full-screen rect are ROP-bound like the others, at 1.6-1.8 cycles per ROP busy cycle
// against 1.01).
int frame_stratum(const FrameWork& w) {
  static_assert(kStageCount < 24, "the stratum key packs a stage mask beside the stage index");
  int mask = 0;
  for (size_t s = 0; s < kStageCount; ++s)
    if (w.busy[s] > 0) mask |= 1 << s;
  const int busiest = int(std::max_element(w.busy.begin(), w.busy.end()) - w.busy.begin());
  return busiest << 24 | mask;
}

// Representatives a stratum of 4 frames or more (the smaller ones are simulated whole):
// T = max(n, 2 B) over its B such strata, 2 each (a variance), then the R = T - 2 B left
// in proportion to their x totals (equal shares when none has any), the floor of each
// share and one more by largest remainder (ties: the lower key) until T are given.
// Before, each stratum took max(2, ceil(n x share)) on its own, which rounds up in every
// stratum: 8 for the torus's 3 strata at n = 5 on default, 6 now (docs/fidelity.md).
std::map<int, size_t> allocate(const std::map<int, std::vector<size_t>>& strata, const std::vector<double>& x,
                               size_t n) {
  std::map<int, double> share;
  double X = 0;
  for (const auto& [h, rest] : strata) {
    if (rest.size() < 4) continue;
    double Xh = 0;
    for (size_t k : rest) Xh += x[k];
    share[h] = Xh;
    X += Xh;
  }
  const size_t T = std::max(n, 2 * share.size()), R = T - 2 * share.size();
  std::map<int, size_t> out;
  std::vector<std::pair<double, int>> rem;  // (-remainder, key): largest first, then the lower key
  size_t given = 0;
  for (auto& [h, Xh] : share) {
    const double q = double(R) * (X > 0 ? Xh / X : 1.0 / double(share.size()));
    out[h] = 2 + size_t(std::floor(q));
    given += out[h];
    rem.emplace_back(-(q - std::floor(q)), h);
  }
  std::sort(rem.begin(), rem.end());
  for (size_t i = 0; given < T && !rem.empty(); ++i, ++given) ++out[rem[i % rem.size()].second];
  return out;
}

// A frame's DRAM read share: its reads' cycles (bytes over the peak) over its x, 0 without.
double read_share(const FrameWork& w) { return w.size() > 0 ? w.dram_read_cycles / w.size() : 0.0; }

// Strata given 4 representatives or more (and fewer than their frames) split in two at the
// median of the frames' read share (the lower half first; ties by frame number), where
// that share varies: the second feature beside x. glmark2's spin on d3d11 is one stratum
// of 98 frames whose y/x runs from 1.56 to 2.37 (coefficient of variation 9 %) and
// follows the frame's DRAM reads (correlation 0.88 with y/x), which x weighs at the peak
// while their latency sets the time; x alone spread its 5 representatives over a ratio
// it does not see (docs/results.md). Returns whether any stratum was split.
bool split_by_reads(const std::vector<FrameWork>& work, std::map<int, std::vector<size_t>>& strata,
                    const std::map<int, size_t>& nh, std::vector<int>& stratum) {
  static_assert(kStageCount <= 24, "the stratum key's bit 29 marks a split stratum's upper half");
  std::map<int, std::vector<size_t>> out;
  bool split = false;
  for (auto& [h, rest] : strata) {
    const auto it = nh.find(h);
    std::vector<size_t> by = rest;
    std::stable_sort(by.begin(), by.end(), [&](size_t a, size_t b) { return read_share(work[a]) < read_share(work[b]); });
    if (it == nh.end() || it->second < 4 || it->second >= rest.size() ||
        read_share(work[by.front()]) == read_share(work[by.back()])) {
      out[h] = rest;
      continue;
    }
    split = true;
    const int upper = h | 1 << 29;
    for (size_t i = 0; i < by.size(); ++i) {
      const int key = i < by.size() / 2 ? h : upper;
      out[key].push_back(by[i]);
      stratum[by[i]] = key;
    }
    for (auto* half : {&out[h], &out[upper]}) std::sort(half->begin(), half->end());
  }
  strata = std::move(out);
  return split;
}

}  // namespace

FramePlan plan_frames(const std::vector<FrameWork>& work, double fraction, uint64_t fill_triangles) {
  if (!(fraction > 0 && fraction <= 1)) throw std::invalid_argument("--frame-sample: F must be in (0, 1]");
  const size_t N = work.size();
  FramePlan p;
  p.x.resize(N);
  p.stratum.assign(N, -1);
  p.chosen.assign(N, false);
  p.certain.assign(N, false);
  p.cluster.assign(N, -1);
  std::map<int, std::vector<size_t>> strata;  // the uncertain frames by bottleneck stage
  size_t M = 0;
  uint64_t through = 0;  // triangles from frame 0 through frame k
  for (size_t k = 0; k < N; ++k) {
    p.x[k] = work[k].size();
    through += work[k].triangles;
    p.certain[k] = k == 0 || k + 1 == N || through < fill_triangles;
    if (p.certain[k]) continue;
    p.stratum[k] = frame_stratum(work[k]);
    strata[p.stratum[k]].push_back(k);
    ++M;
  }
  const size_t n = size_t(std::ceil(fraction * double(M) - 1e-9));
  std::map<int, size_t> nh = allocate(strata, p.x, n);
  if (fraction < 1 && split_by_reads(work, strata, nh, p.stratum)) nh = allocate(strata, p.x, n);
  for (auto& [h, rest] : strata) {
    // A stratum of fewer than 4 frames, or given all its frames, is simulated whole (certain).
    const auto it = nh.find(h);
    if (fraction >= 1 || it == nh.end() || it->second >= rest.size()) {
      for (size_t k : rest) p.certain[k] = true;
      continue;
    }
    std::stable_sort(rest.begin(), rest.end(), [&](size_t a, size_t b) { return p.x[a] < p.x[b]; });
    choose_clusters(p, rest, it->second);
  }
  for (size_t k = 0; k < N; ++k)
    if (p.certain[k]) p.chosen[k] = true;
  return p;
}

FrameSampledResult extrapolate_frames(const FramePlan& plan, const std::vector<double>& y, double confidence) {
  FrameSampledResult r;
  r.confidence = confidence;
  r.frames_total = plan.x.size();
  r.clusters = plan.clusters;
  struct Stratum {
    double X = 0, sx = 0, sy = 0;
    size_t M = 0, n = 0;
    std::vector<size_t> sample;
  };
  std::map<int, Stratum> strata;
  double total = 0;
  for (size_t k = 0; k < plan.x.size(); ++k) {
    if (plan.chosen[k]) {
      r.simulated.push_back(k);
      r.y.push_back(y[k]);
    }
    if (plan.certain[k]) {
      total += y[k];
      continue;
    }
    Stratum& s = strata[plan.stratum[k]];
    ++s.M;
    s.X += plan.x[k];
    if (!plan.chosen[k]) continue;
    ++s.n;
    s.sx += plan.x[k];
    s.sy += y[k];
    s.sample.push_back(k);
  }
  r.frames_simulated = r.simulated.size();
  double var = 0, df_den = 0;
  for (const auto& [h, s] : strata) {
    if (s.n < 2) throw std::logic_error("extrapolate_frames: a stratum with fewer than 2 simulated frames");
    const double R = s.sx > 0 ? s.sy / s.sx : 0;  // no analytic work: plain expansion below
    total += s.sx > 0 ? R * s.X : s.sy / double(s.n) * double(s.M);
    double ss = 0;
    for (size_t k : s.sample) {
      const double e = y[k] - (s.sx > 0 ? R * plan.x[k] : s.sy / double(s.n));
      ss += e * e;
    }
    const double v = double(s.M) * double(s.M) * (1 - double(s.n) / double(s.M)) * ss / double(s.n - 1) / double(s.n);
    var += v;
    df_den += v * v / double(s.n - 1);
  }
  r.cycles = r.ci_low = r.ci_high = total;
  if (var > 0) {  // Student t, Satterthwaite's degrees of freedom
    const double h = student_t_quantile(0.5 + 0.5 * confidence, var * var / df_den) * std::sqrt(var);
    r.ci_low = total - h;
    r.ci_high = total + h;
  }
  return r;
}

std::function<void(const Command&, size_t, uint64_t)> record_command_starts(const Scene& scene,
                                                                           std::vector<uint64_t>& starts) {
  starts.assign(scene.commands.size(), UINT64_MAX);
  return [&scene, &starts](const Command& cmd, size_t, uint64_t cycle) {
    const size_t i = size_t(&cmd - scene.commands.data());
    if (i < starts.size() && starts[i] == UINT64_MAX) starts[i] = cycle;
  };
}

std::vector<uint64_t> span_cycles(const std::vector<FrameSpan>& spans, const std::vector<uint64_t>& starts,
                                  uint64_t end_cycle) {
  std::vector<uint64_t> out;
  for (const FrameSpan& s : spans) {
    const uint64_t from = starts.at(s.begin), to = s.end < starts.size() ? starts[s.end] : end_cycle;
    if (from == UINT64_MAX || to == UINT64_MAX || to < from)
      throw std::logic_error("span_cycles: a frame's first command was not fetched");
    out.push_back(to - from);
  }
  return out;
}

uint64_t CommandStarts::at(size_t first, FrameBoundary b, bool run_first) const {
  const uint64_t c = run_first || b == FrameBoundary::Fetch ? fetch.at(first) : rop.at(first);
  if (c == UINT64_MAX)
    throw std::logic_error(std::string("frame starts: a frame's first command was not ") +
                           (run_first || b == FrameBoundary::Fetch ? "fetched" : "taken by the ROP"));
  return c;
}

void record_command_starts(const Scene& scene, CommandStarts& s, sc::SimOptions& o) {
  o.on_fetch = record_command_starts(scene, s.fetch);
  s.rop.assign(scene.commands.size(), UINT64_MAX);
  o.on_rop_state = [&scene, &s](const Command& cmd, uint64_t cycle) {
    const size_t i = size_t(&cmd - scene.commands.data());
    if (i < s.rop.size() && s.rop[i] == UINT64_MAX) s.rop[i] = cycle;
  };
}

std::vector<uint64_t> span_cycles(const std::vector<FrameSpan>& spans, const CommandStarts& starts, FrameBoundary b,
                                  uint64_t end_cycle) {
  std::vector<uint64_t> out;
  for (size_t k = 0; k < spans.size(); ++k) {
    const uint64_t from = starts.at(spans[k].begin, b, k == 0);
    const size_t next = spans[k].end;  // the next frame's first command, if the run has it
    const uint64_t to = next < starts.fetch.size() ? starts.at(next, b, false) : end_cycle;
    if (to < from) throw std::logic_error("span_cycles: a frame ends before it starts");
    out.push_back(to - from);
  }
  return out;
}

namespace {

// Triangles a command draws (0 for state and 2D commands).
size_t command_triangles(const Command& c) {
  const auto* p = std::get_if<CmdPrimitives>(&c.body);
  if (!p) return 0;
  return p->clip_space() ? triangle_count(p->topology, p->clip_vertices.size()) : triangle_count(*p);
}

// The warm-up's share of its frame's triangles, at least: the chosen frame meets the
// DRAM's queues and open rows the predecessor's last stretch leaves, and the segment's
// DRAM starts idle. Measured at F = 0.05 (docs/fidelity.md): bunny on default, the
// FIFOs' entries alone (32 triangles) left its frames -7.1 .. 0 % off, a tenth of the
// frame -3.5 .. 0 %, a quarter -1.7 .. +0.7 %.
constexpr double kWarmShare = 0.25;

// Where the warm-up before frame k (> 0) starts: the last whole commands before it
// holding at least max(`warm`, kWarmShare of frame k - 1's triangles) triangles (`warm`:
// the FIFOs' entries, the backlog frame k meets at its first fetch), reaching back past
// frame k - 1 into the frames before it when that frame holds fewer (glmark2's texture
// scene: 12 triangles a frame, each 30,000 texture-bound cycles, so command fetch runs
// frames ahead of the texture stage; a one-frame tail left the FIFOs empty and the
// measured frames at 45-68 cycles against 450,000: docs/results.md), at most to the
// scene's start.
size_t warm_start(const Scene& scene, const std::vector<FrameSpan>& spans, size_t k, size_t warm) {
  const FrameSpan& s = spans[k - 1];
  size_t all = 0;
  for (size_t i = s.begin; i < s.end; ++i) all += command_triangles(scene.commands[i]);
  warm = std::max(warm, size_t(std::ceil(kWarmShare * double(all))));
  size_t i = s.end, tri = 0;
  while (i > spans[0].begin && tri < warm) tri += command_triangles(scene.commands[--i]);
  return i;
}

// A run of consecutive chosen frames [first, last), simulated from the scene's commands
// [from, ...): `from` is the warm-up's start in frame first - 1 (frames[first].begin for
// frame 0). The run ends with frame `last`'s first command, when there is one: its
// fetch ends frame last - 1's cycles, as in the full run.
struct Segment {
  size_t first = 0, last = 0, from = 0;
};

std::vector<Segment> segments_of(const Scene& scene, const std::vector<FrameSpan>& spans,
                                 const std::vector<bool>& chosen, size_t warm) {
  std::vector<Segment> out;
  for (size_t k = 0; k < spans.size(); ++k) {
    if (!chosen[k] || (k > 0 && chosen[k - 1])) continue;
    Segment s{k, k, k == 0 ? spans[0].begin : warm_start(scene, spans, k, warm)};
    while (s.last < spans.size() && chosen[s.last]) ++s.last;
    out.push_back(s);
  }
  return out;
}

// The segment's scene (the state commands before `from`, then from `from` to the end
// marker) and where each of its frames starts in it.
Scene segment_scene(const Scene& scene, const std::vector<FrameSpan>& spans, const Segment& s,
                    std::vector<size_t>& frame_at) {
  Scene sub;
  sub.source = scene.source;
  sub.commands = carried_state(scene, s.from);
  const size_t prefix = sub.commands.size();
  const size_t end = s.last < spans.size() ? spans[s.last].begin + 1 : spans.back().end;
  sub.commands.insert(sub.commands.end(), scene.commands.begin() + std::ptrdiff_t(s.from),
                      scene.commands.begin() + std::ptrdiff_t(end));
  frame_at.clear();
  for (size_t k = s.first; k <= s.last && k < spans.size(); ++k) frame_at.push_back(prefix + spans[k].begin - s.from);
  return sub;
}

// One segment in a child process (SystemC elaborates once a process) from the reference's
// framebuffer and memory state at its start (null: the scene's start): the frames' y,
// each from its start to the next's by `b` (the segment's first frame: its fetch when it
// is frame 0, the run's start).
nlohmann::json run_segment(const Scene& sub, const std::vector<size_t>& frame_at, size_t frames,
                           const ArchParams& arch, FrameBoundary b, bool from_start, const WarmState* warm,
                           uint64_t scanout_phase) {
  return run_in_child([&] {
    CommandStarts starts;
    sc::SimOptions o;
    record_command_starts(sub, starts, o);
    // The DRAM backlog (MemorySystem::backlog_cycles) when each frame_at command is first
    // fetched: the one each measured frame meets and leaves (reported).
    const MemorySystem* mem = nullptr;
    std::vector<uint64_t> backlog(frame_at.size(), 0);
    o.on_memory_system = [&mem](const MemorySystem& m) { mem = &m; };
    o.on_fetch = [&, record = o.on_fetch](const Command& c, size_t t, uint64_t cycle) {
      const size_t i = size_t(&c - sub.commands.data());
      const bool first = i < starts.fetch.size() && starts.fetch[i] == UINT64_MAX;
      record(c, t, cycle);
      for (size_t f = 0; first && mem && f < frame_at.size(); ++f)
        if (frame_at[f] == i) backlog[f] = mem->backlog_cycles(cycle);
    };
    o.initial_fb = warm ? &warm->fb : nullptr;
    o.warm_memory = warm ? warm->mem.get() : nullptr;
    o.scanout_phase = scanout_phase;
    const sc::SimResult r = sc::simulate_scene(sub, arch, o);
    std::vector<uint64_t> y;
    for (size_t i = 0; i < frames; ++i) {
      const uint64_t to = i + 1 < frame_at.size() ? starts.at(frame_at[i + 1], b, false) : r.cycles;
      y.push_back(to - starts.at(frame_at[i], b, i == 0 && from_start));
    }
    return nlohmann::json{{"y", y}, {"backlog", backlog}, {"cycles", r.cycles}};
  });
}

// Every segment run, in order: the chosen frames' y and what the warm-ups cost.
struct SegmentRuns {
  std::vector<double> y;  // by frame; 0 where not chosen
  // By frame: the DRAM backlog at the frame's start and at its end (the next frame's
  // first fetch; 0 at the scene's end), cycles.
  std::vector<double> backlog_in, backlog_out;
  uint64_t cycles = 0;    // the runs' own cycles, summed
  size_t warm_frames = 0, warm_triangles = 0;
  double warm_share = 0;
  std::vector<uint64_t> scanout_phase;  // each segment's (SimOptions::scanout_phase)
};

// Where a segment starts in the full run, estimated for its scan-out's phase
// (SimOptions::scanout_phase): the frames before it at their measured y where simulated,
// else x times the y/x ratio measured so far on frames of their kind (frame_stratum; no
// such frame yet: on every frame measured so far; none: frame 0's; frame 0, a cold start
// whose y/x is atypical, counts only there), less each frame of the warm-up tail by the
// tail's share of that frame's triangles. Segments run in frame order, so the first is
// frame 0's, from cycle 0.
class StartEstimate {
 public:
  StartEstimate(const FramePlan& plan, const std::vector<FrameWork>& work) : x_(plan.x) {
    for (const FrameWork& w : work) kind_.push_back(frame_stratum(w));
  }
  void measured(size_t k, double y) {
    Ratio& r = k == 0 ? first_ : ratio_[kind_[k]];  // frame 0 (a cold start, the pipeline's fill): its own
    r.y += y, r.x += x_[k];
    if (k > 0) all_.y += y, all_.x += x_[k];
  }
  // The full run's cycle at the start of frame `first`, then minus each tail frame's
  // share of its cycles (`tail`: frame, the warm-up's triangles over the frame's).
  uint64_t cycle(size_t first, const std::vector<std::pair<size_t, double>>& tail, const std::vector<double>& y) const {
    double t = 0;
    for (size_t j = 0; j < first; ++j) t += y[j] > 0 ? y[j] : guess(j);
    for (const auto& [j, share] : tail) t -= share * (y[j] > 0 ? y[j] : guess(j));
    return t > 0 ? uint64_t(std::llround(t)) : 0;
  }

 private:
  struct Ratio {
    double y = 0, x = 0;
  };
  double guess(size_t j) const {
    const auto it = ratio_.find(kind_[j]);
    const Ratio& r = it != ratio_.end() && it->second.x > 0 ? it->second : all_.x > 0 ? all_ : first_;
    return x_[j] * (r.x > 0 ? r.y / r.x : 1.0);
  }
  const std::vector<double>& x_;
  std::vector<int> kind_;
  std::map<int, Ratio> ratio_;
  Ratio all_, first_;  // every frame measured but frame 0; frame 0
};

// The warm-up tail's frames (those before s.first it reaches into, usually s.first - 1
// alone: warm_start), each with the tail's share of its triangles (1 for a frame without
// any); the tail's triangles into `tri`.
std::vector<std::pair<size_t, double>> tail_shares(const Scene& scene, const std::vector<FrameSpan>& spans,
                                                   const Segment& s, size_t& tri) {
  std::vector<std::pair<size_t, double>> out;
  tri = 0;
  for (size_t j = s.first; j-- > 0 && spans[j].end > s.from;) {
    size_t in = 0, all = 0;
    for (size_t i = spans[j].begin; i < spans[j].end; ++i) {
      const size_t t = command_triangles(scene.commands[i]);
      all += t;
      if (i >= s.from) in += t;
    }
    tri += in;
    out.emplace_back(j, all ? double(in) / double(all) : 1.0);
  }
  return out;
}

SegmentRuns run_segments(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch,
                         FrameBoundary b, const std::vector<Segment>& segs, const WarmStates& warm, StartEstimate& at) {
  SegmentRuns out;
  out.y.assign(spans.size(), 0.0);
  out.backlog_in.assign(spans.size(), 0.0);
  out.backlog_out.assign(spans.size(), 0.0);
  std::vector<size_t> frame_at;
  for (const Segment& s : segs) {
    // The reference's state at the segment's start (functional_pass's snapshot); none at
    // the scene's start (cold).
    const WarmState* w = s.from == 0 ? nullptr : warm.at(s.from).get();
    size_t tri = 0;
    const auto tail = tail_shares(scene, spans, s, tri);
    const uint64_t phase = s.from == 0 ? 0 : at.cycle(s.first, tail, out.y);
    const Scene sub = segment_scene(scene, spans, s, frame_at);
    const nlohmann::json j = run_segment(sub, frame_at, s.last - s.first, arch, b, s.first == 0, w, phase);
    const auto ys = j.at("y").get<std::vector<uint64_t>>();
    const auto bs = j.at("backlog").get<std::vector<uint64_t>>();
    for (size_t k = s.first; k < s.last; ++k) {
      const size_t i = k - s.first;
      out.y[k] = double(ys.at(i));
      at.measured(k, out.y[k]);
      // Reported, not counted: y + backlog_out - backlog_in as the estimator's y was tried
      // and made 3 of 13 pairs worse (docs/results.md).
      out.backlog_in[k] = double(bs.at(i));
      out.backlog_out[k] = i + 1 < bs.size() ? double(bs[i + 1]) : 0.0;
    }
    out.cycles += j.at("cycles").get<uint64_t>();
    out.scanout_phase.push_back(phase);
    out.warm_frames += tail.size();
    out.warm_triangles += tri;
    for (const auto& [f, share] : tail) out.warm_share += share;
  }
  return out;
}

}  // namespace

FrameSampledResult simulate_frame_sampled(const Scene& scene, const ArchParams& arch, double fraction,
                                          double confidence, size_t snapshot_budget) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<FrameSpan> spans = frame_spans(scene.commands);
  const FrameBoundary b = frame_boundary(scene, spans, arch);
  // The FIFOs' entries: with frames measured at command fetch, the least warm-up tail (the
  // backlog a frame meets at its first fetch) and the pipeline fill whose frames are
  // certain; at the ROP neither (a frame's cycles are its work's there: frames.h).
  const size_t W = b == FrameBoundary::Fetch ? triangle_path_entries(arch.timing) : 0;
  // One functional pass: the whole scene's counts, each frame's DRAM bytes read, and the
  // state at every frame's possible warm-up start (the plan needs the bytes first).
  std::vector<size_t> starts;
  for (size_t k = 1; k < spans.size(); ++k) starts.push_back(warm_start(scene, spans, k, W));
  FunctionalPass pass = functional_pass(scene, spans, arch, starts, snapshot_budget);
  EstimateResult whole;
  std::vector<FrameWork> work = frame_work(scene, arch, &whole, &pass.stats);
  add_frame_dram_reads(arch, pass.dram_bytes_read, whole.dram_peak_bytes_per_cycle, work);
  const FramePlan plan = plan_frames(work, spans.size() < kFrameSampledMinFrames ? 1.0 : fraction, W);
  const std::vector<Segment> segs = segments_of(scene, spans, plan.chosen, W);
  std::vector<size_t> froms;
  for (const Segment& s : segs) froms.push_back(s.from);
  const double fallback = warm_states_for(scene, arch, froms, pass.warm);  // snapshots over the budget
  StartEstimate at(plan, work);
  const SegmentRuns runs = run_segments(scene, spans, arch, b, segs, pass.warm, at);
  FrameSampledResult r = extrapolate_frames(plan, runs.y, confidence);
  r.fraction = fraction;
  r.boundary = b;
  r.frame_x = plan.x;
  r.frame_stratum = plan.stratum;
  r.cycles_simulated = runs.cycles;
  r.warm_frames = runs.warm_frames;
  r.warm_triangles = runs.warm_triangles;
  r.warm_frame_share = runs.warm_share;
  r.warm_functional_seconds = pass.seconds + fallback;
  r.scanout_phase = runs.scanout_phase;
  for (size_t k : r.simulated) {
    r.backlog_in.push_back(runs.backlog_in[k]);
    r.backlog_out.push_back(runs.backlog_out[k]);
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

nlohmann::json FrameSampledResult::to_json() const {
  const double far = std::max(cycles - ci_low, ci_high - cycles);
  return {{"fidelity_level", "frame-sampled"},
          {"cycles", uint64_t(std::llround(cycles))},
          {"cycles_ci_low", ci_low},
          {"cycles_ci_high", ci_high},
          {"cycles_error_bound", cycles > 0 ? far / cycles : 0.0},
          {"confidence", confidence},
          {"frames_total", frames_total},
          {"frames_simulated", frames_simulated},
          {"frame_sample", fraction},
          {"frame_boundary", frame_boundary_name(boundary)},
          {"frame_clusters", clusters},
          {"frames_simulated_list", simulated},
          {"frames_x", frame_x},
          {"frames_stratum", frame_stratum},
          {"frames_simulated_cycles", y},
          {"frames_simulated_backlog_in", backlog_in},
          {"frames_simulated_backlog_out", backlog_out},
          {"cycles_simulated", cycles_simulated},
          {"warm_frames", warm_frames},
          {"warm_triangles", warm_triangles},
          {"warm_frame_share", warm_frame_share},
          {"frames_detailed", double(frames_simulated) + warm_frame_share},
          {"warm_functional_seconds", warm_functional_seconds},
          {"segment_scanout_phase", scanout_phase},
          {"wall_seconds", wall_seconds}};
}

}  // namespace rastsim::fidelity
