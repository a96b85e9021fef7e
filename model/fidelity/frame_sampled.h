// SPDX-License-Identifier: Apache-2.0
// Frame sampling, the frame-sampled fidelity level (`rastsim simulate --frame-sample F`,
// docs/fidelity.md "Frame sampling"): of a multi-frame scene, the SystemC model runs a
// few representative frames and the rest are estimated from the analytic walk's work.
//
// - Features (functional, model/fidelity/frames.h frame_work): each frame's per-stage
//   busy cycles from the analytic walk; x = the busiest stage's (the frame's analytic
//   bottleneck work) plus, with memory.model = "dram", the frame's DRAM bytes read over
//   the DRAM's peak (add_frame_dram_reads). The reference model runs once for the whole
//   level (functional_pass.h: the estimate's whole counts, the per-frame bytes and the
//   warm-up snapshots).
// - Frame boundaries (frames.h FrameBoundary): at the ROP when every frame after the
//   first starts with a state item, else at command fetch.
// - Certain frames, always simulated: the first (the pipeline fills, the state is set),
//   the last (the drain and the frame-end resolve and flush are in its cycles) and, with
//   boundaries at fetch, those after the first whose successor starts while the FIFOs
//   still fill (fewer triangles from frame 0 than their entries).
// - Strata: the other M frames by their analytic bottleneck stage and the set of stages
//   with any work (a frame whose 2D fill or clear dominates, or that has one at all, is
//   not timed like one whose fragments do). A stratum of fewer than 4 frames is
//   certain; the B others share T = max(ceil(F M), 2 B) representatives, 2 each, the
//   rest in proportion to their x totals (floors, then largest remainders); a stratum
//   given all its frames is certain. A stratum given 4 or more is split in two at the
//   median of its frames' DRAM read share (dram_read_cycles / x, where it varies), and
//   the representatives allocated again over the halves (the same rule, the same total).
// - Clusters (deterministic, no seed): a stratum's frames sorted by x (ties by frame
//   number) and cut into n_h runs of consecutive frames of equal size (sizes differing
//   by at most one): one-dimensional clustering by equal counts. Each cluster's
//   representative is its member whose x is nearest the cluster's mean x (ties: the
//   lower frame number).
// - Each run of consecutive chosen frames is one SystemC run (in a child process: one
//   elaboration a process) that starts from the reference model's state at its warm-up's
//   start (framebuffer, the ROP caches' lines and dirty bits, fast-clear flags:
//   SimOptions::initial_fb, warm_memory; functional_pass's snapshot) with its scan-out
//   at the phase the run's start has in the full run, estimated (SimOptions::
//   scanout_phase), and simulates, unmeasured, the tail of the frame before it (its last
//   commands holding a quarter of its triangles; at fetch boundaries at least the FIFOs'
//   entries, reaching into the frames before it when it holds fewer: the backlog and
//   DRAM state the chosen frame meets), then the frames, then the next frame's first
//   command. The DRAM starts idle (docs/fidelity.md says what that leaves). A chosen
//   frame's y: from its start to the next frame's (the last: to the end), as
//   frames[].cycles of the full run.
// - Estimator: y of the certain frames + per stratum the ratio estimator X_h (sum y /
//   sum x) over its representatives; variance M_h^2 (1 - n_h/M_h) s_e^2 / n_h from the
//   ratio residuals e = y - R_h x (a simple random sample's formula); Student t with
//   Satterthwaite's degrees of freedom at the confidence asked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "fidelity/frames.h"
#include "fidelity/functional_pass.h"
#include "fidelity/sampled.h"
#include "ref/scene.h"

namespace rastsim::sc {
struct SimOptions;
}

namespace rastsim::fidelity {

struct FramePlan {
  std::vector<double> x;        // each frame's FrameWork::size(), cycles
  std::vector<bool> chosen;     // simulated in detail
  std::vector<bool> certain;    // the first and the last frame
  std::vector<int> stratum;     // bottleneck stage << 24 | mask of stages with work; -1: certain
  std::vector<int> cluster;     // -1 for a certain frame
  size_t clusters = 0;
};
// The plan for `work` (frame_work's) at fraction F in (0, 1]. F = 1 chooses every frame.
// `fill_triangles` (the FIFOs' entries, triangle_path_entries): a frame is also certain
// while the triangles from frame 0 through it are fewer, since its successor's first
// fetch then comes while the pipeline fills and its cycles are not its work's (glmark2's
// texture scene, 12 triangles a frame: frames 1 and 2 take 48 cycles each in the full
// run and their work lands in the last frame's drain; docs/results.md).
FramePlan plan_frames(const std::vector<FrameWork>& work, double fraction, uint64_t fill_triangles = 0);

struct FrameSampledResult {
  double cycles = 0, ci_low = 0, ci_high = 0, confidence = kDefaultConfidence;
  double fraction = 0;
  FrameBoundary boundary = FrameBoundary::Fetch;  // where the frames' y were measured (frames.h)
  size_t frames_total = 0, frames_simulated = 0, clusters = 0;
  // Every frame's x (FramePlan::x, cycles) and stratum key (-1: certain): the plan, so the
  // estimator can be replayed on a full run's frames[].cycles (docs/results.md).
  std::vector<double> frame_x;
  std::vector<int> frame_stratum;
  std::vector<size_t> simulated;  // the frames simulated in detail
  std::vector<double> y;          // their measured cycles, in the same order
  // Their DRAM backlog (MemorySystem::backlog_cycles) at their first fetch and at the
  // next frame's, cycles; empty from extrapolate_frames alone.
  std::vector<double> backlog_in, backlog_out;
  uint64_t cycles_simulated = 0;  // the sub-run's own cycles
  size_t warm_frames = 0;         // frames whose tail warms a chosen frame (its predecessor, or more: warm_start)
  size_t warm_triangles = 0;      // the triangles those tails draw, simulated unmeasured
  double warm_frame_share = 0;    // the tails' share of their frames' triangles, summed (frames' worth)
  double warm_functional_seconds = 0;  // wall time of the one functional pass (functional_pass.h), any fallback's too
  // Each segment's scan-out phase (SimOptions::scanout_phase): its estimated start in the
  // full run, core cycles (0 for a cold start).
  std::vector<uint64_t> scanout_phase;
  double wall_seconds = 0;
  // cycles, cycles_ci_low/high, cycles_error_bound (the interval's farther end from
  // cycles, relative), confidence, frames_total, frames_simulated, frame_sample,
  // frames_simulated_list, fidelity_level = "frame-sampled", ...
  nlohmann::json to_json() const;
};

// From the measured y of the chosen frames (y[k], ignored where !chosen[k]).
FrameSampledResult extrapolate_frames(const FramePlan& plan, const std::vector<double>& y,
                                      double confidence = kDefaultConfidence);

// The whole level: features, plan, one SystemC run of the chosen frames (elaborates:
// once per process), extrapolation. A scene of fewer than kFrameSampledMinFrames frames
// is simulated whole.
inline constexpr size_t kFrameSampledMinFrames = 4;
// `snapshot_budget`: bytes of warm-up snapshots the one functional pass may keep
// (functional_pass.h); past it a second pass warms the rest, with the same result.
FrameSampledResult simulate_frame_sampled(const Scene& scene, const ArchParams& arch, double fraction,
                                          double confidence = kDefaultConfidence,
                                          size_t snapshot_budget = kWarmSnapshotBudget);

// A frame's cycles (frames[].cycles) run from its start to the next frame's (the last
// frame: to the end of the run), so they sum to the run's cycles; frame 0 starts with the
// run, the others where FrameBoundary says (frames.h). on_fetch for a run of `scene`
// (the scene object the run reads): records into `starts` the cycle command fetch started
// each command (by index), the first time.
std::function<void(const Command&, size_t, uint64_t)> record_command_starts(const Scene& scene,
                                                                           std::vector<uint64_t>& starts);
// Each span's cycles from the recorded starts: [start of its first command, start of the
// first command after it), the last to `end_cycle`.
std::vector<uint64_t> span_cycles(const std::vector<FrameSpan>& spans, const std::vector<uint64_t>& starts,
                                  uint64_t end_cycle);

// Both starts of each command of a run's scene (by index; UINT64_MAX: none): command
// fetch starting it, and the ROP taking it (state items only, SimOptions::on_rop_state).
struct CommandStarts {
  std::vector<uint64_t> fetch, rop;
  // Where frame `first` (its first command's index) starts: its fetch when it is the
  // run's first frame (`run_first`) or under FrameBoundary::Fetch, else the ROP's take.
  uint64_t at(size_t first, FrameBoundary b, bool run_first) const;
};
// Sets o.on_fetch and o.on_rop_state to fill `s` (which, with `scene`, must outlive the run).
void record_command_starts(const Scene& scene, CommandStarts& s, sc::SimOptions& o);
// span_cycles with the spans' starts by `b` (the first span: its fetch).
std::vector<uint64_t> span_cycles(const std::vector<FrameSpan>& spans, const CommandStarts& starts, FrameBoundary b,
                                  uint64_t end_cycle);

}  // namespace rastsim::fidelity
