// SPDX-License-Identifier: Apache-2.0
#include "fidelity/tolerance.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "estimate/estimate.h"
#include "fidelity/frame_sampled.h"
#include "fidelity/frames.h"
#include "fidelity/run_child.h"
#include "fidelity/sampled.h"

namespace rastsim::fidelity {

// The sampled level's relative error bound: the interval's farther end from the estimate.
double sampled_error(const nlohmann::json& s) {
  const double c = s["cycles"].get<double>();
  return c > 0 ? std::max(s["cycles_ci_high"].get<double>() - c, c - s["cycles_ci_low"].get<double>()) / c : 0.0;
}

namespace {

// Half-width ~ sqrt((1 - f) / f) (the finite-population factor over the sample size, for
// batches and frames alike): the f that would reach `tol` from a pilot's `err` at `f`,
// with a 1.2 margin.
double predicted_fraction(double f, double err, double tol) {
  const double want = (1 - f) / f * (tol / (1.2 * err)) * (tol / (1.2 * err));
  return 1 / (1 + want);
}

// Step 2 on a multi-frame scene: the frame-sampled level, a pilot at F = 0.05, then the F
// its interval predicts (if <= 0.5), each in a forked child; {} (and run_full, reason)
// when neither is within tol. `half`: the analytic bounds' half-width, for the reason.
nlohmann::json choose_frame_sampled(const Scene& scene, const ArchParams& arch, double tol, double half, bool& run_full,
                                    std::string& reason) {
  char buf[400];
  double f = 0.05, err = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    nlohmann::json s = run_in_child([&] { return simulate_frame_sampled(scene, arch, f).to_json(); });
    err = s["cycles_error_bound"].get<double>();
    if (s["frames_simulated"] == s["frames_total"]) {  // nothing left out: no cheaper than the full run
      std::snprintf(buf, sizeof buf,
                    "the analytic bounds are %.2f %% wide, above %.2f %%, and frame sampling at F = %.3f would "
                    "simulate every frame: the full SystemC run answers",
                    100 * half, 100 * tol, f);
      break;
    }
    if (err <= tol) {
      std::snprintf(buf, sizeof buf,
                    "the analytic bounds are %.2f %% wide, the frame-sampled level's %.0f %% interval at F = %.3f "
                    "(%zu of %zu frames) is within %.2f %% (<= %.2f %%)",
                    100 * half, 100 * s["confidence"].get<double>(), f, s["frames_simulated"].get<size_t>(),
                    s["frames_total"].get<size_t>(), 100 * err, 100 * tol);
      s["fidelity_reason"] = buf;
      return s;
    }
    std::snprintf(buf, sizeof buf,
                  "the analytic bounds are %.2f %% wide and the frame-sampled interval %.2f %% at F = %.3f, above "
                  "%.2f %%: the full SystemC run answers",
                  100 * half, 100 * err, f, 100 * tol);
    const double next = predicted_fraction(f, err, tol);
    if (next > 0.5 || next <= f) break;  // simulating half the frames or more is not cheaper
    f = next;
  }
  reason = buf;
  run_full = true;
  return {};
}

}  // namespace

nlohmann::json choose_level(const Scene& scene, const ArchParams& arch, double tol, uint64_t seed, bool& run_full,
                            std::string& reason) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  char buf[400];
  const EstimateResult est = estimate_scene(scene, arch);
  const double lo = double(est.cycles_lower_bound), hi = double(est.cycles_upper_bound);
  const double mid = 0.5 * (lo + hi), half = mid > 0 ? 0.5 * (hi - lo) / mid : 0.0;
  if (half <= tol) {
    std::snprintf(buf, sizeof buf, "the analytic bounds [%.0f, %.0f] are within %.2f %% of their midpoint (<= %.2f %%)",
                  lo, hi, 100 * half, 100 * tol);
    return {{"fidelity_level", "analytic"}, {"cycles", uint64_t(std::llround(mid))}, {"cycles_error_bound", half},
            {"cycles_lower_bound", est.cycles_lower_bound}, {"cycles_upper_bound", est.cycles_upper_bound},
            {"fidelity_reason", buf}, {"wall_seconds", wall()}};
  }
  if (frame_spans(scene.commands).size() >= kFrameSampledMinFrames) {
    nlohmann::json s = choose_frame_sampled(scene, arch, tol, half, run_full, reason);
    if (!run_full) s["wall_seconds"] = wall();
    return s;
  }
  double f = 0.1, err = 0;
  nlohmann::json s;
  for (int attempt = 0; attempt < 2; ++attempt) {
    s = run_in_child([&] { return simulate_sampled(scene, arch, f, seed).to_json(); });
    err = sampled_error(s);
    if (s["units_simulated"] == s["units_total"]) {  // nothing left out: no cheaper than the full run
      std::snprintf(buf, sizeof buf,
                    "the analytic bounds are %.2f %% wide, above %.2f %%, and the sampled level would simulate every "
                    "unit (all certain): the full SystemC run answers",
                    100 * half, 100 * tol);
      reason = buf;
      run_full = true;
      return {};
    }
    if (err <= tol) {
      std::snprintf(buf, sizeof buf,
                    "the analytic bounds are %.2f %% wide, the sampled level's %.0f %% interval at F = %.3f is "
                    "within %.2f %% (<= %.2f %%)",
                    100 * half, 100 * s["confidence"].get<double>(), f, 100 * err, 100 * tol);
      s["cycles_error_bound"] = err;
      s["fidelity_reason"] = buf;
      s["wall_seconds"] = wall();
      return s;
    }
    const double next = predicted_fraction(f, err, tol);
    if (next > 0.5 || next <= f) break;  // sampling half the frame or more is not cheaper
    f = next;
  }
  std::snprintf(buf, sizeof buf,
                "the analytic bounds are %.2f %% wide and the sampled interval %.2f %% at F = %.3f, above %.2f %%: "
                "the full SystemC run answers",
                100 * half, 100 * err, f, 100 * tol);
  reason = buf;
  run_full = true;
  return {};
}

}  // namespace rastsim::fidelity
