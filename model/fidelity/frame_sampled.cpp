// SPDX-License-Identifier: Apache-2.0
#include "fidelity/frame_sampled.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "fidelity/student_t.h"
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

// The chosen frames' commands in order. A frame left out keeps its viewport and scissor
// commands (the state the next frames inherit); the frame just before a chosen one is
// kept whole, a warm-up (simulated, not measured): the chosen frame starts with the
// backlog and the memory state (ROP caches' lines, fast-clear flags, DRAM queues and open
// rows) its predecessor leaves in the full run. A tail of the predecessor's last W
// triangles (the FIFOs' entries) gave the backlog but not the memory state: with
// memory.model = "dram" frames ran -23..+63 % off their full-run cycles, against
// -4.3..+3.3 % with the whole predecessor (docs/fidelity.md). `measured[k]`: the span of
// chosen frame k in the sub-scene; `warm_frames`, `warm_triangles`: what the warm-ups hold.
Scene chosen_frames(const Scene& scene, const std::vector<FrameSpan>& spans, const std::vector<bool>& chosen,
                    std::vector<FrameSpan>& measured, size_t& warm_frames, size_t& warm_triangles) {
  Scene sub;
  sub.source = scene.source;
  measured.assign(spans.size(), FrameSpan{});
  warm_frames = warm_triangles = 0;
  for (size_t k = 0; k < spans.size(); ++k) {
    const size_t at = sub.commands.size();
    const bool warms = !chosen[k] && k + 1 < spans.size() && chosen[k + 1];
    warm_frames += warms;
    for (size_t i = spans[k].begin; i < spans[k].end; ++i) {
      const CommandBody& b = scene.commands[i].body;
      if (chosen[k] || warms || std::holds_alternative<CmdViewport>(b) || std::holds_alternative<CmdScissor>(b)) {
        sub.commands.push_back(scene.commands[i]);
        if (warms) warm_triangles += command_triangles(scene.commands[i]);
      }
    }
    if (chosen[k]) measured[k] = {at, sub.commands.size(), spans[k].line};
  }
  return sub;
}

}  // namespace

FrameSampledResult simulate_frame_sampled(const Scene& scene, const ArchParams& arch, double fraction,
                                          double confidence) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<FrameSpan> spans = frame_spans(scene.commands);
  EstimateResult whole;
  std::vector<FrameWork> work = frame_work(scene, arch, &whole);
  add_frame_dram_reads(scene, arch, whole.dram_peak_bytes_per_cycle, work);
  FramePlan plan = plan_frames(work, spans.size() < kFrameSampledMinFrames ? 1.0 : fraction);
  std::vector<FrameSpan> measured;
  size_t warm_frames = 0, warm_triangles = 0;
  const Scene sub = chosen_frames(scene, spans, plan.chosen, measured, warm_frames, warm_triangles);
  std::vector<uint64_t> starts;
  sc::SimOptions opts;
  opts.on_fetch = record_command_starts(sub, starts);
  const sc::SimResult run = sc::simulate_scene(sub, arch, opts);
  // A chosen frame runs to the next simulated command after it (a chosen frame, or a
  // carried state command of one left out), the last to the end.
  std::vector<double> y(spans.size(), 0.0);
  for (size_t k = 0; k < spans.size(); ++k) {
    if (!plan.chosen[k]) continue;
    const uint64_t from = starts.at(measured[k].begin);
    const uint64_t to = measured[k].end < starts.size() ? starts[measured[k].end] : run.cycles;
    y[k] = double(to - from);
  }
  FrameSampledResult r = extrapolate_frames(plan, y, confidence);
  r.fraction = fraction;
  r.cycles_simulated = run.cycles;
  r.warm_frames = warm_frames;
  r.warm_triangles = warm_triangles;
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
          {"wall_seconds", wall_seconds}};
}

}  // namespace rastsim::fidelity
