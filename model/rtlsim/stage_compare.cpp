// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/stage_compare.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"

namespace rastsim::rtlsim {

std::vector<StageAgreement> compare_stages(const std::vector<StageRecord>& model, const std::vector<StageRecord>& rtl) {
  std::vector<StageAgreement> v;
  for (const StageRecord& r : rtl)
    for (const StageRecord& m : model) {
      if (m.name != r.name) continue;
      StageAgreement a{r.name, m, r, 0};
      if (r.busy > 0) a.busy_error = (double(m.busy) - double(r.busy)) / double(r.busy);
      else if (m.busy > 0) a.busy_error = 1;
      v.push_back(std::move(a));
    }
  return v;
}

const StageAgreement* worst_stage(const std::vector<StageAgreement>& a) {
  const StageAgreement* w = nullptr;
  for (const StageAgreement& s : a)
    if (!w || std::abs(s.busy_error) > std::abs(w->busy_error)) w = &s;
  return w;
}

nlohmann::json stages_json(const std::vector<StageAgreement>& a) {
  nlohmann::json j = nlohmann::json::object();
  for (const StageAgreement& s : a)
    j[s.name] = {{"busy_rtl", s.rtl.busy},           {"busy_model", s.model.busy},
                 {"stalled_rtl", s.rtl.stalled},     {"stalled_model", s.model.stalled},
                 {"starved_rtl", s.rtl.starved},     {"starved_model", s.model.starved},
                 {"transactions_rtl", s.rtl.transactions}, {"transactions_model", s.model.transactions},
                 {"busy_error", s.busy_error}};
  return j;
}

namespace {

std::string row(const std::string& stage, size_t k, const StageSpan& s) {
  return stage + "," + std::to_string(k) + "," + std::to_string(s.start) + "," + std::to_string(s.end);
}

void write_csv(const std::filesystem::path& path, const std::vector<StageAgreement>& a, bool model, uint64_t& rows) {
  AtomicFile file(path.string());  // whole or not at all (util/atomic_file.h)
  std::ofstream& f = file.stream();
  f << "stage,transaction,start_cycle,end_cycle\n";
  for (const StageAgreement& s : a) {
    const std::vector<StageSpan>& spans = model ? s.model.spans : s.rtl.spans;
    for (size_t k = 0; k < spans.size(); ++k, ++rows) f << row(s.name, k, spans[k]) << "\n";
  }
  file.commit();
}

}  // namespace

TraceDiff write_trace_diff(const std::string& dir, const std::vector<StageAgreement>& a) {
  std::filesystem::create_directories(dir);
  TraceDiff d;
  write_csv(std::filesystem::path(dir) / "model.csv", a, true, d.rows_model);
  write_csv(std::filesystem::path(dir) / "rtl.csv", a, false, d.rows_rtl);
  uint64_t line = 2, earliest_start = UINT64_MAX;  // model.csv line of the stage's first row (after the header)
  for (const StageAgreement& s : a) {
    const auto& m = s.model.spans;
    const auto& r = s.rtl.spans;
    for (size_t k = 0; k < std::max(m.size(), r.size()); ++k) {
      std::string what;
      uint64_t start = 0;
      if (k >= m.size() || k >= r.size()) {
        what = s.name + " transaction " + std::to_string(k) + ": only the " + (k < m.size() ? "model" : "RTL") +
               " has it (" + std::to_string(m.size()) + " model, " + std::to_string(r.size()) + " RTL transactions)";
        start = k < m.size() ? m[k].start : r[k].start;
      } else if (m[k].start != r[k].start || m[k].end != r[k].end) {
        what = s.name + " transaction " + std::to_string(k) + ": model [" + std::to_string(m[k].start) + ", " +
               std::to_string(m[k].end) + "), RTL [" + std::to_string(r[k].start) + ", " + std::to_string(r[k].end) +
               ")";
        // Where the two sides part: the earlier start, or with equal starts the earlier end.
        start = m[k].start != r[k].start ? std::min(m[k].start, r[k].start) : std::min(m[k].end, r[k].end);
      } else {
        continue;
      }
      if (!d.differs) d.first = what + " (model.csv line " + std::to_string(line + k) + ")";
      d.differs = true;
      if (start < earliest_start) {
        earliest_start = start;
        d.earliest = what;
      }
    }
    line += m.size();
  }
  return d;
}

}  // namespace rastsim::rtlsim
