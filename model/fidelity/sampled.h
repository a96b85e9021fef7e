// SPDX-License-Identifier: Apache-2.0
// The sampled fidelity level (`rastsim simulate --sample F`, docs/fidelity.md): the
// SystemC model runs a stratified random sample of the scene's triangle batches and the
// frame's cycle count is extrapolated with a confidence interval.
//
// - Units: the command stream cut into batches of about `batch` triangles (at least
//   twice the FIFOs' total entries, plan_units; cut only
//   where a strip's next triangle is even, so a sliced strip keeps its winding), plus
//   every other command (state, clears, 2D) as a unit of its own.
// - Certain units, always simulated: every non-triangle command, the batches after each
//   of them until every stage has had twice the command's busiest stage's cycles of
//   work (they absorb a clear's or 2D draw's ROP time), the head (batches until
//   as many triangles as all FIFOs hold entries: the pipeline's fill, while command
//   fetch runs ahead), the last batch (drain, resolve pass) and every batch of a stratum
//   too small to sample.
// - Strata: the batch's analytic bottleneck stage (the stage with the most busy cycles
//   in the batch, by the estimate's walk, model/estimate). Auxiliary x: those busy cycles.
// - One SystemC run of the chosen units in program order (one elaboration); a chosen unit
//   whose predecessor is left out is preceded by that predecessor's last triangles
//   (warm-up, unmeasured). A unit's measured cycles y: from command fetch starting it to
//   command fetch starting the next simulated unit or warm-up (the last: to the end).
// - Estimator: certain units' y plus, per stratum, the ratio estimator X_h sum(y)/sum(x);
//   variance N_h^2 (1 - n_h/N_h) s_e^2 / n_h from the ratio residuals, s_e^2 at least
//   the certain batches' y/x variance times the stratum's mean x squared (a floor for
//   small samples whose ratios agree by chance); Student t with Satterthwaite's degrees
//   of freedom. All units chosen: the run is the full scene and
//   the interval has zero width.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "estimate/estimate.h"
#include "ref/scene.h"

namespace rastsim::fidelity {

// The default confidence of the sampled level's interval.
inline constexpr double kDefaultConfidence = 0.95;

struct Piece {
  size_t command = 0;     // index into the scene's commands
  size_t k0 = 0, k1 = 0;  // triangles [k0, k1) of a primitive command; 0, 0 for others
  bool whole = false;     // a non-triangle command or an empty primitive command
};

struct Unit {
  std::vector<Piece> pieces;  // consecutive in program order
  bool certain = false;       // always simulated
  int stratum = -1;           // analytic bottleneck stage (stage index, timing/stage_table.h)
  double x = 0;               // analytic busy cycles of that stage in this unit
  uint64_t triangles = 0;
};

struct UnitPlan {
  std::vector<Unit> units;
  size_t batch = 0;         // triangles a batch
  uint64_t head_triangles = 0;  // the certain head: the FIFOs' total entries
  size_t warm_triangles = 0;    // warm-up before a unit whose predecessor is left out
  EstimateResult analytic;  // the whole scene's estimate (bounds)
};

// Cuts `scene` into units and weighs them by the analytic walk. batch = 0: the largest
// of 8, total triangles / 200 and twice all FIFOs' entries (so the context a batch
// inherits from the one before it is a small part of it), made even.
UnitPlan plan_units(const Scene& scene, const ArchParams& arch, size_t batch = 0);

// Entries of every FIFO between two triangle-path stages (timing/stage_table.h): how far,
// in transactions, command fetch can run ahead of a bottleneck downstream.
uint64_t triangle_path_entries(const TimingParams& p);

// A stratified simple random sample without replacement of the plan's uncertain units,
// n = ceil(fraction x N) allocated to strata in proportion to their analytic work, at
// least 2 a stratum; plus every certain unit. chosen[i]: unit i is simulated.
std::vector<bool> draw_sample(const UnitPlan& plan, double fraction, uint64_t seed);

// The chosen units' commands in program order (a primitive command sliced to the chosen
// triangles; adjacent chosen pieces of one command merged, so choosing every unit gives
// back the scene's commands). A chosen unit whose predecessor (a triangle batch) is left
// out is preceded by a warm-up: the last plan.warm_triangles triangles of that
// predecessor, simulated but not measured, so the unit starts with its true context in
// the FIFOs. segments: (sub-scene command, its triangle) where each measured unit or
// warm-up starts, in program order, with the unit (SIZE_MAX for a warm-up).
struct SubScene {
  Scene scene;
  struct Segment {
    size_t command = 0, triangle = 0;
    size_t unit = SIZE_MAX;
  };
  std::vector<Segment> segments;
  size_t warm_triangles = 0;  // triangles simulated as warm-up
};
SubScene sub_scene(const Scene& scene, const UnitPlan& plan, const std::vector<bool>& chosen);

struct SampledResult {
  double cycles = 0;  // point estimate of the full simulation's cycles
  double ci_low = 0, ci_high = 0;
  double confidence = kDefaultConfidence;
  double sample_fraction = 0;           // as asked
  double work_fraction_simulated = 0;   // analytic work of the simulated units / all
  size_t units_total = 0, units_simulated = 0, units_certain = 0, strata = 0;
  size_t batch_triangles = 0;
  double degrees_of_freedom = 0;
  double variance_floor = 0;      // the context term added to the sampling variance
  size_t warm_triangles = 0;      // triangles simulated as warm-up, unmeasured
  uint64_t cycles_simulated = 0;  // the sampled run's own cycles
  uint64_t seed = 0;
  double wall_seconds = 0;        // planning + the SystemC run + the estimator
  EstimateResult analytic;

  // cycles, cycles_ci_low, cycles_ci_high, confidence, sample_fraction, units_total,
  // units_simulated, wall_seconds, fidelity_level = "sampled", and the details.
  nlohmann::json to_json() const;
};

// From the measured cycles of the chosen units (y[u], ignored for units not chosen).
SampledResult extrapolate(const UnitPlan& plan, const std::vector<bool>& chosen, const std::vector<double>& y,
                          double confidence = kDefaultConfidence);

// The whole level: plan, sample, one SystemC run (elaborates: once per process),
// extrapolate. 0 < fraction <= 1.
SampledResult simulate_sampled(const Scene& scene, const ArchParams& arch, double fraction, uint64_t seed,
                               double confidence = kDefaultConfidence);

}  // namespace rastsim::fidelity
