// SPDX-License-Identifier: Apache-2.0
// The sampled level (model/fidelity/sampled.h, docs/fidelity.md) against the full
// SystemC run:
//
// - choosing every unit simulates the scene itself: the sub-scene is the scene's
//   commands, the estimate is the full run's cycles and the interval has zero width;
// - coverage: over seeded trials (sampling seeds x fractions x scenes x configs,
//   including the shipped traces), the full run's cycles lie inside the 95 % interval
//   in at least 95 % of trials. Each simulation runs in a forked child.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fidelity/sampled.h"
#include "fidelity/tolerance.h"
#include "sim_harness.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

std::string source(const std::string& rel) { return std::string(RASTSIM_SOURCE_DIR) + "/" + rel; }

Config config_file(const std::string& name) {
  Config cfg;
  cfg.load_file(source("configs/" + name + ".toml"));
  cfg.validate();
  return cfg;
}

TEST(ScSampled, EveryUnitChosenIsTheFullRun) {
  for (const char* name : {"default", "desktop"}) {
    const Config cfg = config_file(name);
    for (const Scene& scene : {load_trace(source("traces/torus.trace")), random_scene(7, 128, 96, 300)}) {
      const fidelity::UnitPlan plan = fidelity::plan_units(scene, ArchParams::resolve(cfg));
      const std::vector<bool> all = fidelity::draw_sample(plan, 1.0, 1);
      EXPECT_TRUE(std::all_of(all.begin(), all.end(), [](bool b) { return b; }));
      const fidelity::SubScene sub = fidelity::sub_scene(scene, plan, all);
      ASSERT_EQ(sub.scene.commands.size(), scene.commands.size());
      const nlohmann::json full = run_isolated([&] { return simulate_stats(scene, cfg); });
      const nlohmann::json s = run_isolated([&] { return fidelity::simulate_sampled(scene, ArchParams::resolve(cfg), 1.0, 1).to_json(); });
      ASSERT_FALSE(s.contains("error")) << s;
      EXPECT_EQ(s["cycles"], full["cycles"]) << name;
      EXPECT_EQ(s["cycles_ci_low"].get<double>(), s["cycles_ci_high"].get<double>());
      EXPECT_EQ(s["units_simulated"], s["units_total"]);
    }
  }
}

// One trial's outcome, printed for the docs' table.
struct Coverage {
  int trials = 0, covered = 0, sampled = 0;  // sampled: trials that left a unit out
};

// The scenes where sampling leaves units out: torus (x1, x4) and three random
// 2500-triangle scenes (state changes, clears) on every config, including the cases the
// first version missed (torus default and d3d11 at F = 0.1, torus x4 desktop, random
// scenes on embedded with its slow clears). The shipped small traces are left out: every
// unit of theirs is certain, so the answer is exact (EveryUnitChosenIsTheFullRun covers
// that). Measured: docs/fidelity.md, "Coverage".
TEST(ScSampled, IntervalCoversTheFullRun) {
  struct Case {
    std::string name;
    Scene scene;
  };
  std::vector<Case> scenes = {{"torus.trace", load_trace(source("traces/torus.trace"))},
                              {"torus x4", repeat_scene(load_trace(source("traces/torus.trace")), 4)}};
  for (uint64_t seed : {11, 12, 13})
    scenes.push_back({"random " + std::to_string(seed), random_scene(seed, 128, 128, 2500)});
  const std::vector<std::string> configs = {"default", "d3d11", "desktop", "embedded"};
  const std::vector<double> fractions = {0.1, 0.25};
  const int seeds = 5;
  Coverage all;
  for (const Case& c : scenes) {
    for (const std::string& cname : configs) {
      const Config cfg = config_file(cname);
      const nlohmann::json full = run_isolated([&] { return simulate_stats(c.scene, cfg); });
      ASSERT_FALSE(full.contains("error")) << full;
      const double truth = full["cycles"].get<double>();
      Coverage here;
      for (double f : fractions)
        for (int s = 1; s <= seeds; ++s) {
          const nlohmann::json r =
              run_isolated([&] { return fidelity::simulate_sampled(c.scene, ArchParams::resolve(cfg), f, uint64_t(s)).to_json(); });
          ASSERT_FALSE(r.contains("error")) << r;
          const bool in = r["cycles_ci_low"].get<double>() <= truth && truth <= r["cycles_ci_high"].get<double>();
          ++here.trials;
          here.covered += in;
          all.sampled += r["units_simulated"] != r["units_total"];
          if (r["units_simulated"] != r["units_total"])
            std::printf("  trial %s %s F=%.2f seed=%d err %+.3f%% half %.3f%% floor %s covered %d units %s/%s\n",
                        c.name.c_str(), cname.c_str(), f, s, 100 * (r["cycles"].get<double>() / truth - 1),
                        100 * (r["cycles_ci_high"].get<double>() - r["cycles_ci_low"].get<double>()) / 2 / truth,
                        r["variance_floor"].dump().c_str(), int(in), r["units_simulated"].dump().c_str(),
                        r["units_total"].dump().c_str());
          if (!in)
            std::printf("  miss: %s %s F=%.2f seed=%d: full %.0f, estimate %s [%.1f, %.1f], %s/%s units\n",
                        c.name.c_str(), cname.c_str(), f, s, truth, r["cycles"].dump().c_str(),
                        r["cycles_ci_low"].get<double>(), r["cycles_ci_high"].get<double>(),
                        r["units_simulated"].dump().c_str(), r["units_total"].dump().c_str());
        }
      std::printf("%-22s %-9s covered %d/%d\n", c.name.c_str(), cname.c_str(), here.covered, here.trials);
      all.trials += here.trials;
      all.covered += here.covered;
    }
  }
  std::printf("coverage: %d/%d trials (%.1f %%), %d of them sampled (not every unit simulated)\n", all.covered,
              all.trials, 100.0 * all.covered / all.trials, all.sampled);
  EXPECT_GE(all.covered, 0.95 * all.trials) << all.covered << "/" << all.trials;
  const int sampled_covered = all.covered - (all.trials - all.sampled);  // the others are exact
  // A 95 % interval covers a trial with probability 0.95, so the covered count of n
  // trials is binomial(n, 0.95): expecting >= 0.95 n would fail a sound method about
  // half the time. The test rejects the method when so few covered would happen with
  // probability under 1 % (a one-sided binomial test): n = 50 allows 43.
  double p_at_most = 0;
  for (int k = 0; k <= sampled_covered; ++k) {
    // C(n, k) 0.95^k 0.05^(n - k), through logarithms.
    const double term = std::exp(std::lgamma(all.sampled + 1.0) - std::lgamma(k + 1.0) - std::lgamma(all.sampled - k + 1.0) +
                    k * std::log(0.95) + (all.sampled - k) * std::log(0.05));
    p_at_most += term;
  }
  std::printf("sampled trials covered %d/%d: P(at most that many | 95 %% coverage) = %.4f\n", sampled_covered,
              all.sampled, p_at_most);
  EXPECT_GE(p_at_most, 0.01) << sampled_covered << "/" << all.sampled << " sampled trials";
}


// --tolerance (fidelity::choose_level): the analytic level answers when its bounds are
// within the tolerance; whichever level answers, the full run's cycles lie within
// cycles x (1 +- cycles_error_bound) (analytic: always, by the proven bounds; sampled:
// with its interval's confidence, so checked on fixed seeds; systemc: exact).
TEST(ScSampled, ToleranceBoundHoldsForTheLevelThatAnswers) {
  struct Case {
    std::string name, config;
    Scene scene;
    double tol;
    const char* want;  // the level that must answer, or nullptr: any
    bool fixed_memory = true;  // memory.model = fixed instead of the config's dram
  };
  const Scene torus = load_trace(source("traces/torus.trace"));
  // The rule's three levels are exercised with the fixed per-access costs: with the shipped
  // configs' memory.model = dram there is no analytic upper bound (docs/estimate.md) and the
  // sampled intervals are wider than these tolerances (the DRAM's waits vary from batch to
  // batch beyond what the analytic walk predicts), so every case would fall through to the
  // full run. The last two cases keep the configs' dram: whatever level answers, its bound holds.
  const std::vector<Case> cases = {
      {"primitives.trace", "desktop", load_trace(source("traces/primitives.trace")), 0.20, "analytic"},
      {"fill_rule.trace", "desktop", load_trace(source("traces/fill_rule.trace")), 0.35, "analytic"},
      {"primitives.trace", "desktop", load_trace(source("traces/primitives.trace")), 0.05, nullptr},
      {"torus.trace", "default", torus, 0.05, nullptr},
      {"torus.trace", "default", torus, 0.50, nullptr},
      {"torus x4", "default", repeat_scene(torus, 4), 0.10, nullptr},
      {"random 12", "embedded", random_scene(12, 128, 128, 2500), 0.10, nullptr},
      {"torus.trace", "default", torus, 0.50, nullptr, false},
      {"random 12", "embedded", random_scene(12, 128, 128, 2500), 0.10, nullptr, false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + " " + c.config + " tolerance " + std::to_string(c.tol) + (c.fixed_memory ? " fixed" : " dram"));
    Config cfg = config_file(c.config);
    if (c.fixed_memory) cfg.apply_override("memory.model=fixed");
    const nlohmann::json full = run_isolated([&] { return simulate_stats(c.scene, cfg); });
    ASSERT_FALSE(full.contains("error")) << full;
    const double truth = full["cycles"].get<double>();
    bool run_full = false;
    std::string reason;
    nlohmann::json j = fidelity::choose_level(c.scene, ArchParams::resolve(cfg), c.tol, 1, run_full, reason);
    const std::string level = run_full ? "systemc" : j["fidelity_level"].get<std::string>();
    std::printf("  %-18s %-9s %-5s tol %4.1f %%: %s %s\n", c.name.c_str(), c.config.c_str(),
                c.fixed_memory ? "fixed" : "dram", 100 * c.tol, level.c_str(),
                run_full ? reason.c_str() : j["fidelity_reason"].get<std::string>().c_str());
    if (c.want) {
      EXPECT_EQ(level, c.want);
    }
    if (run_full) continue;  // the caller runs the full model: exact
    const double cycles = j["cycles"].get<double>(), bound = j["cycles_error_bound"].get<double>();
    EXPECT_LE(bound, c.tol);
    EXPECT_LE(std::abs(truth - cycles), cycles * bound + 0.5) << "truth " << truth << ", " << j.dump();
  }
}

}  // namespace
}  // namespace rastsim::sctest
