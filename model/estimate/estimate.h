// SPDX-License-Identifier: Apache-2.0
// The analytic fidelity level: cycles of the timed pipeline (model/sc) bounded and
// estimated without event simulation (docs/estimate.md).
//
// - Walks the scene's transactions stage by stage with the reference model's functions
//   (assemble_triangle, setup_triangle, the tile walks, fine_raster_partial, draw2d_ops)
//   and sums each transaction's cost through the SAME TimingParams functions the
//   SystemC stages call, so each stage's busy total equals the SystemC stage's `busy`.
// - No interpolation, depth test or framebuffer: costs depend only on counts (with
//   raster.samples > 1, on the coverage masks: fine tests x S, ROP accesses by the
//   compression rule, shaded fragments per aa mode, and the frame-end resolve pass).
// - Lower bound: max over stages with work of stage_fill_cycles + busy.
// - Upper bound: sum of every stage's busy cycles plus every pipeline-latency wait
//   (setup's and interpolation's extra latency times the transactions they emit).
// - Point estimate: lower + kEstimateBlend * (upper - lower).
// - With memory.model = "dram": a bandwidth bound joins the lower bound (the line fills the
//   ROP waits for cannot move faster than the DRAM's peak), and there is no upper bound
//   (the DRAM's latencies under load are not bounded by the counts).
// - A scene drawn with a texture bound: the texture stage's busy cycles from its sample
//   rate, fetches and combine alone (TimingParams::texture_batch_cycles without quads and
//   misses), a lower bound; no upper bound (the texture cache's misses are not counted).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "config/timing_params.h"
#include "timing/stage_table.h"
#include "ref/pipeline.h"
#include "ref/scene.h"

namespace rastsim {

// Where between the bounds the point estimate sits: the median of (SystemC - lower) /
// (upper - lower) over the shipped traces and configs (docs/estimate.md), which is 0.
inline constexpr double kEstimateBlend = 0.0;

struct EstimateStage {
  uint64_t busy = 0;              // cycles, equal to the SystemC stage's busy
  uint64_t transactions_out = 0;  // written to the next FIFO (as the SystemC stage's)
};

struct EstimateResult {
  std::array<EstimateStage, kStageCount> stages{};  // by stage index (timing/stage_table.h)
  RenderStats render;  // geometry counters only (no fragments_passed, CRC, interp error)
  // The ROP's traffic, as SimResult's (exact: accesses follow from the coverage masks
  // and aa mode alone, not from the depth test).
  uint64_t rop_accesses = 0, framebuffer_bytes = 0, resolve_cycles = 0;
  uint64_t latency_waits = 0;  // the upper bound's sum of pipeline-latency waits, cycles
  uint64_t cycles_lower_bound = 0, cycles_upper_bound = 0, cycles_estimate = 0;
  // The lower bound's two parts: max over stages of fill + busy, and the bandwidth bound
  // (0 with memory.model = "fixed").
  uint64_t stage_lower_bound = 0, bandwidth_lower_bound = 0;
  // memory.model = "dram" or a texture bound: no upper bound; cycles_upper_bound is kNoUpperBound.
  static constexpr uint64_t kNoUpperBound = ~uint64_t{0};
  bool has_upper_bound() const { return cycles_upper_bound != kNoUpperBound; }
  // memory.model = "dram": the reference's DRAM bytes (render --stats' dram_bytes_read and
  // dram_bytes_written), the DRAM's peak bytes a core cycle (channels x bus bytes x
  // transfers a clock x DRAM clock / core clock) and the bound of the bytes read and
  // written together, which the DRAM's last completion (simulate's memory.dram.end_cycle)
  // cannot precede.
  uint64_t dram_bytes_read = 0, dram_bytes_written = 0;
  double dram_peak_bytes_per_cycle = 0;
  uint64_t dram_lower_bound = 0;
  double core_mhz = 0;
  double wall_seconds = 0;

  // cycles_lower_bound (with stage_lower_bound, bandwidth_lower_bound), cycles_upper_bound
  // (null without one), cycles_estimate, wall_seconds, core_mhz, with memory.model = "dram"
  // dram_bytes_read, dram_bytes_written, dram_peak_bytes_per_cycle, dram_lower_bound;
  // rop_accesses, framebuffer_bytes, resolve_cycles, stages.<name>.{busy,transactions_out},
  // and the geometry counters (with the multisample ones).
  nlohmann::json to_json() const;
};

// Called before each fetch transaction of the walk: each command (triangle 0), and each
// triangle k of a primitive command, with the totals so far (stages' busy and
// transactions_out, counters). Differences between calls give a piece of the scene's
// per-stage work (the sampled level's auxiliary variable, model/fidelity/sampled.h).
using EstimateProgress = std::function<void(size_t command, size_t triangle, const EstimateResult& so_far)>;

// The analytic estimate of `scene` on `arch`. Throws SceneError on bad input (the
// reference model's message). `reference`: the reference model's counts of the whole
// scene (render_scene's, finish() included) when the caller has them (frame sampling's
// one functional pass): the bounds that need them (the DRAM bytes, early Z's kept
// fragments) take them instead of a reference run of their own. Null: run it here.
EstimateResult estimate_scene(const Scene& scene, const ArchParams& arch, const EstimateProgress& progress = {},
                              const RenderStats* reference = nullptr);

}  // namespace rastsim
