// SPDX-License-Identifier: Apache-2.0
// Stage-by-stage agreement of the SystemC model and the RTL co-simulation
// (docs/microarchitecture.md "Stage statistics"): a total cycle count can agree by
// accident while two stages' errors cancel, so every stage's busy, stalled and starved
// cycles are compared, and, for `rastsim cosim --trace-diff DIR`, every transaction's
// start and end cycle.
//
// - compare_stages(): the stages present on both sides, in pipeline order, with each
//   side's figures and the busy-cycle error (model - rtl) / rtl.
// - stages_json(): `stages.<name>.{busy,stalled,starved,transactions}_{rtl,model}` and
//   `busy_error` for --stats.
// - write_trace_diff(): DIR/model.csv and DIR/rtl.csv (stage,transaction,start_cycle,
//   end_cycle; the same row order on both sides, so `diff` lines them up) and the first
//   transaction whose timing differs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rtlsim/cosim.h"

namespace rastsim::rtlsim {

// A model-side report (sc::StageReport: name, busy, stalled, starved, transactions, spans
// {t0, t1}) as a StageRecord; a template so this layer needs no SystemC.
template <class Report>
std::vector<StageRecord> stage_records(const std::vector<Report>& reports) {
  std::vector<StageRecord> v;
  for (const Report& s : reports) {
    StageRecord r{s.name, s.busy, s.stalled, s.starved, s.transactions, {}};
    for (const auto& sp : s.spans) r.spans.push_back(StageSpan{sp.t0, sp.t1});
    v.push_back(std::move(r));
  }
  return v;
}

struct StageAgreement {
  std::string name;
  StageRecord model, rtl;
  double busy_error = 0;  // (model - rtl) / rtl; 0 when both are 0, 1 when only the RTL's is 0
};

// The stages of `rtl` that `model` has too, in `rtl`'s order.
std::vector<StageAgreement> compare_stages(const std::vector<StageRecord>& model, const std::vector<StageRecord>& rtl);

// The stage with the largest |busy_error| (null when `a` is empty).
const StageAgreement* worst_stage(const std::vector<StageAgreement>& a);

nlohmann::json stages_json(const std::vector<StageAgreement>& a);

struct TraceDiff {
  uint64_t rows_model = 0, rows_rtl = 0;
  bool differs = false;
  std::string first;     // the first differing row (as `diff` shows it), "" when none
  // The differing transaction where the sides part first in time (the earlier of the
  // two starts when they differ, else the earlier end; ties: the first in row order),
  // "" when none: with a change of timing in one transaction, that transaction.
  std::string earliest;
};

// Writes DIR/model.csv and DIR/rtl.csv (DIR is created) and finds the first difference.
// Throws std::runtime_error naming the file when one cannot be written.
TraceDiff write_trace_diff(const std::string& dir, const std::vector<StageAgreement>& a);

}  // namespace rastsim::rtlsim
