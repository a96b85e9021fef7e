// SPDX-License-Identifier: Apache-2.0
#include "fidelity/frame_sampled.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <numeric>
#include <span>
#include <stdexcept>

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

}  // namespace

FramePlan plan_frames(const std::vector<FrameWork>& work, double fraction) {
  if (!(fraction > 0 && fraction <= 1)) throw std::invalid_argument("--frame-sample: F must be in (0, 1]");
  const size_t N = work.size();
  FramePlan p;
  p.x.resize(N);
  p.stratum.assign(N, -1);
  p.chosen.assign(N, false);
  p.certain.assign(N, false);
  p.cluster.assign(N, -1);
  std::map<int, std::vector<size_t>> strata;  // the uncertain frames by bottleneck stage
  double X = 0;
  size_t M = 0;
  for (size_t k = 0; k < N; ++k) {
    p.x[k] = work[k].size();
    p.certain[k] = k == 0 || k + 1 == N;
    if (p.certain[k]) continue;
    p.stratum[k] = frame_stratum(work[k]);
    strata[p.stratum[k]].push_back(k);
    X += p.x[k];
    ++M;
  }
  const size_t n = size_t(std::ceil(fraction * double(M) - 1e-9));
  for (auto& [h, rest] : strata) {
    double Xh = 0;
    for (size_t k : rest) Xh += p.x[k];
    // In proportion to the stratum's work, at least 2 (a variance); a stratum of fewer
    // than 4 frames is simulated whole (certain).
    size_t nh = std::max<size_t>(2, size_t(std::ceil(double(n) * (X > 0 ? Xh / X : 1.0 / double(strata.size())))));
    if (rest.size() < 4 || nh >= rest.size()) {
      for (size_t k : rest) p.certain[k] = true;
      continue;
    }
    std::stable_sort(rest.begin(), rest.end(), [&](size_t a, size_t b) { return p.x[a] < p.x[b]; });
    choose_clusters(p, rest, nh);
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

// Where the warm-up in frame `s` starts: its last whole commands holding at least
// max(`warm`, kWarmShare of its triangles) triangles (`warm`: the FIFOs' entries, the
// backlog the next frame meets at its first fetch).
size_t warm_start(const Scene& scene, const FrameSpan& s, size_t warm) {
  size_t all = 0;
  for (size_t i = s.begin; i < s.end; ++i) all += command_triangles(scene.commands[i]);
  warm = std::max(warm, size_t(std::ceil(kWarmShare * double(all))));
  size_t i = s.end, tri = 0;
  while (i > s.begin && tri < warm) tri += command_triangles(scene.commands[--i]);
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
    Segment s{k, k, k == 0 ? spans[0].begin : warm_start(scene, spans[k - 1], warm)};
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
// framebuffer and memory state at its start (null: the scene's start): the frames' y.
nlohmann::json run_segment(const Scene& sub, const std::vector<size_t>& frame_at, size_t frames,
                           const ArchParams& arch, const Framebuffer* fb, const RopMemory* mem) {
  return run_in_child([&] {
    std::vector<uint64_t> starts;
    sc::SimOptions o;
    o.on_fetch = record_command_starts(sub, starts);
    o.initial_fb = fb;
    o.warm_memory = mem;
    const sc::SimResult r = sc::simulate_scene(sub, arch, o);
    std::vector<uint64_t> y;
    for (size_t i = 0; i < frames; ++i) {
      const uint64_t to = i + 1 < frame_at.size() ? starts.at(frame_at[i + 1]) : r.cycles;
      y.push_back(to - starts.at(frame_at[i]));
    }
    return nlohmann::json{{"y", y}, {"cycles", r.cycles}};
  });
}

// Every segment run, in order: the chosen frames' y and what the warm-ups cost.
struct SegmentRuns {
  std::vector<double> y;  // by frame; 0 where not chosen
  uint64_t cycles = 0;    // the runs' own cycles, summed
  size_t warm_frames = 0, warm_triangles = 0;
  double warm_share = 0, functional_seconds = 0;
};

SegmentRuns run_segments(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch,
                         const std::vector<Segment>& segs) {
  // The functional warm-up: the reference model through every command before each
  // segment's start (framebuffer, ROP caches, fast-clear flags), one pass in all.
  RenderStats ref_stats;
  SceneRenderer ref(arch.raster, ref_stats, {}, Framebuffer::kDefaultTileLog2, 1, arch.memory);
  SegmentRuns out;
  out.y.assign(spans.size(), 0.0);
  size_t done = 0;
  std::vector<size_t> frame_at;
  for (const Segment& s : segs) {
    const auto f0 = std::chrono::steady_clock::now();
    ref.run(std::span<const Command>(scene.commands).subspan(done, s.from - done));
    done = s.from;
    const bool cold = s.from == 0;
    const Framebuffer& fb = ref.frame_so_far();
    out.functional_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count();
    const Scene sub = segment_scene(scene, spans, s, frame_at);
    const nlohmann::json j = run_segment(sub, frame_at, s.last - s.first, arch, cold ? nullptr : &fb,
                                         cold ? nullptr : ref.memory());
    const auto ys = j.at("y").get<std::vector<uint64_t>>();
    for (size_t k = s.first; k < s.last; ++k) out.y[k] = double(ys.at(k - s.first));
    out.cycles += j.at("cycles").get<uint64_t>();
    if (s.first == 0) continue;
    size_t tri = 0, all = 0;
    for (size_t i = spans[s.first - 1].begin; i < spans[s.first - 1].end; ++i) {
      const size_t t = command_triangles(scene.commands[i]);
      all += t;
      if (i >= s.from) tri += t;
    }
    ++out.warm_frames;
    out.warm_triangles += tri;
    out.warm_share += all ? double(tri) / double(all) : 1.0;
  }
  return out;
}

}  // namespace

FrameSampledResult simulate_frame_sampled(const Scene& scene, const ArchParams& arch, double fraction,
                                          double confidence) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<FrameSpan> spans = frame_spans(scene.commands);
  EstimateResult whole;
  std::vector<FrameWork> work = frame_work(scene, arch, &whole);
  add_frame_dram_reads(scene, arch, whole.dram_peak_bytes_per_cycle, work);
  const FramePlan plan = plan_frames(work, spans.size() < kFrameSampledMinFrames ? 1.0 : fraction);
  const SegmentRuns runs =
      run_segments(scene, spans, arch, segments_of(scene, spans, plan.chosen, triangle_path_entries(arch.timing)));
  FrameSampledResult r = extrapolate_frames(plan, runs.y, confidence);
  r.fraction = fraction;
  r.cycles_simulated = runs.cycles;
  r.warm_frames = runs.warm_frames;
  r.warm_triangles = runs.warm_triangles;
  r.warm_frame_share = runs.warm_share;
  r.warm_functional_seconds = runs.functional_seconds;
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
          {"frame_clusters", clusters},
          {"frames_simulated_list", simulated},
          {"frames_simulated_cycles", y},
          {"cycles_simulated", cycles_simulated},
          {"warm_frames", warm_frames},
          {"warm_triangles", warm_triangles},
          {"warm_frame_share", warm_frame_share},
          {"frames_detailed", double(frames_simulated) + warm_frame_share},
          {"warm_functional_seconds", warm_functional_seconds},
          {"wall_seconds", wall_seconds}};
}

}  // namespace rastsim::fidelity
