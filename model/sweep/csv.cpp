// SPDX-License-Identifier: Apache-2.0
// The sweep's CSV (sweep.h): written a row at a time so that an interrupted sweep
// keeps every finished row, and read back by --resume.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sweep/sweep.h"
#include "util/version.h"

namespace rastsim::sweep {

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
std::string csv_value(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// The records of a CSV file (RFC 4180: quoted fields may hold commas, quotes and newlines).
std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> rec;
  std::string field;
  bool quoted = false, any = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c != '"') field += c;
      else if (i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else quoted = false;
    } else if (c == '"') {
      quoted = any = true;
    } else if (c == ',') {
      rec.push_back(std::move(field)), field.clear(), any = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      if (any || !field.empty()) rec.push_back(std::move(field)), records.push_back(std::move(rec));
      field.clear(), rec.clear(), any = false;
    } else {
      field += c, any = true;
    }
  }
  if (quoted) throw std::runtime_error(path + ": ends inside a quoted field");
  if (any || !field.empty()) rec.push_back(std::move(field)), records.push_back(std::move(rec));
  return records;
}

// The stats' provenance object (app/common.h): not columns, the leading columns hold it.
constexpr const char* kProvenance = "provenance";

// The version of the binary that ran a point, from its stats' provenance (a Slurm task
// runs the binary found at its path when it starts); this binary's for a point that
// failed before writing stats.
std::string run_version(const nlohmann::json& stats) {
  const nlohmann::json::json_pointer at("/" + std::string(kProvenance) + "/rastsim_version");
  if (stats.is_object() && stats.contains(at) && stats[at].is_string()) return stats[at];
  return rastsim_version();
}

// "stages": {"rop": {"busy": 3}} -> "stages.rop.busy" = 3; the top-level key `skip` left out.
void flatten(const nlohmann::json& j, const std::string& prefix, std::map<std::string, std::string>& out,
             const std::string& skip = "") {
  for (const auto& [k, v] : j.items()) {
    const std::string key = prefix.empty() ? k : prefix + "." + k;
    if (prefix.empty() && k == skip) continue;
    if (v.is_object()) flatten(v, key, out);
    else out[key] = csv_value(v);
  }
}

// Dotted keys compared part by part: the order in which the (sorted) stats JSON lists them.
bool path_less(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  for (;;) {
    const size_t ea = std::min(a.find('.', i), a.size()), eb = std::min(b.find('.', j), b.size());
    const int c = a.compare(i, ea - i, b, j, eb - j);
    if (c != 0) return c < 0;
    if (ea == a.size() || eb == b.size()) return ea == a.size() && eb != b.size();
    i = ea + 1, j = eb + 1;
  }
}

std::string row_key(const std::string& scene, const std::string& level, const std::string& hash) {
  return scene + '\n' + level + '\n' + hash;
}

}  // namespace

bool is_wall_time_column(const std::string& c) {
  return c == "wall_seconds" || c == "sim_wall_seconds" || c == "simulated_cycles_per_second";
}

std::string row_level(const std::string& level, bool area) { return area ? level + "+area" : level; }

Csv::Csv(std::string path, const std::vector<Axis>& axes, std::vector<FixedSet> fixed, std::string level)
    : path_(std::move(path)), axes_(axes), fixed_(std::move(fixed)), level_(std::move(level)) {}

std::vector<std::string> Csv::leading_columns() const {
  std::vector<std::string> cols{"scene"};
  for (const auto& a : axes_) cols.push_back(a.key);
  cols.insert(cols.end(), {"level", "config_hash", "status"});
  for (const auto& f : fixed_) cols.push_back(f.key);
  cols.push_back("rastsim_version");
  return cols;
}

Csv::Cells Csv::cells_of(const Point& p) const {
  Cells c;
  if (p.status == 0) flatten(p.stats, "", c, kProvenance);
  for (auto it = c.begin(); it != c.end();) it = it->second.empty() ? c.erase(it) : std::next(it);
  c["scene"] = p.scene;
  for (size_t i = 0; i < axes_.size(); ++i) c[axes_[i].key] = p.values[i];
  c["level"] = level_;
  c["config_hash"] = p.config_hash;
  c["status"] = p.status == 0 ? "ok" : p.error;
  for (const auto& f : fixed_) c[f.key] = f.value;
  c["rastsim_version"] = run_version(p.stats);
  return c;
}

void Csv::merge_columns(const Cells& row) {
  const auto leading = leading_columns();
  std::vector<std::string> keys;
  for (const auto& [k, v] : row)
    if (!v.empty() && std::find(leading.begin(), leading.end(), k) == leading.end()) keys.push_back(k);
  std::sort(keys.begin(), keys.end(), path_less);
  for (const auto& k : keys)
    if (std::find(stat_columns_.begin(), stat_columns_.end(), k) == stat_columns_.end()) stat_columns_.push_back(k);
}

size_t Csv::resume(std::vector<Point>& points) {
  if (!std::filesystem::exists(path_)) return 0;
  const auto records = read_csv(path_);
  if (records.empty()) return 0;
  const auto leading = leading_columns();
  const auto& header = records[0];
  if (header.size() < leading.size() || !std::equal(leading.begin(), leading.end(), header.begin())) {
    std::string want, got;
    for (const auto& c : leading) want += (want.empty() ? "" : ", ") + c;
    for (size_t i = 0; i < std::min(header.size(), leading.size()); ++i) got += (got.empty() ? "" : ", ") + header[i];
    throw std::runtime_error(path_ + ": --resume needs a CSV of this sweep's columns (" + want + "), it has (" + got +
                             "); write to another --output or drop --resume");
  }
  std::map<std::string, size_t> by_key;
  for (size_t i = 0; i < points.size(); ++i) by_key.emplace(row_key(points[i].scene, level_, points[i].config_hash), i);
  size_t found = 0;
  std::set<std::string> seen;
  for (size_t r = 1; r < records.size(); ++r) {
    const auto& rec = records[r];
    if (rec.size() != header.size()) continue;  // cut short (cannot happen unless edited)
    Cells c;
    for (size_t i = 0; i < rec.size(); ++i)
      if (!rec[i].empty() || i < leading.size()) c[header[i]] = rec[i];
    if (c["status"] != "ok") continue;  // a failed row runs again
    const std::string key = row_key(c["scene"], c["level"], c["config_hash"]);
    if (!seen.insert(key).second) continue;  // a row twice (cannot happen unless edited)
    const auto it = by_key.find(key);
    if (it == by_key.end()) {
      foreign_.push_back(std::move(c));
      continue;
    }
    Point& p = points[it->second];
    for (size_t i = 0; i < axes_.size(); ++i) c[axes_[i].key] = p.values[i];  // this sweep's spelling
    p.status = 0;
    rows_[it->second] = std::move(c);
    ++found;
  }
  if (!foreign_.empty())
    std::cerr << "sweep: " << path_ << ": keeping " << foreign_.size()
              << " finished rows that are not points of this sweep (after its own)\n";
  return found;
}

std::string Csv::line_of(const Cells& row) const {
  std::string line;
  for (const auto& c : leading_columns()) line += (line.empty() ? "" : ",") + csv_field(row.at(c));
  for (const auto& c : stat_columns_) {
    const auto it = row.find(c);
    line += "," + (it == row.end() ? std::string() : csv_field(it->second));
  }
  return line + "\n";
}

void Csv::rewrite() {
  std::vector<const Cells*> rows;
  for (size_t j : written_) rows.push_back(&rows_.at(j));
  for (const auto& f : foreign_) rows.push_back(&f);
  stat_columns_.clear();
  for (const Cells* r : rows) merge_columns(*r);
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream os(tmp, std::ios::trunc);
    if (!os) throw std::runtime_error(path_ + ": cannot open " + tmp + " for writing");
    std::string header;
    for (const auto& c : leading_columns()) header += (header.empty() ? "" : ",") + csv_field(c);
    for (const auto& c : stat_columns_) header += "," + csv_field(c);
    os << header << "\n";
    for (const Cells* r : rows) os << line_of(*r);
    os.close();
    if (!os) throw std::runtime_error(tmp + ": write failed");
  }
  std::filesystem::rename(tmp, path_);
}

void Csv::write_all(const std::vector<Point>& points) {
  written_.clear();
  for (size_t i = 0; i < points.size(); ++i)
    if (rows_.count(i)) written_.push_back(i);
  rewrite();
}

void Csv::add(const Point& p, size_t i) {
  rows_[i] = cells_of(p);
  written_.push_back(i);
  const size_t before = stat_columns_.size();
  merge_columns(rows_[i]);
  if (stat_columns_.size() != before) return rewrite();  // a new column: the whole file again
  const std::string line = line_of(rows_[i]);
  std::FILE* f = std::fopen(path_.c_str(), "a");
  if (!f) throw std::runtime_error(path_ + ": cannot open for appending");
  const bool ok = std::fwrite(line.data(), 1, line.size(), f) == line.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error(path_ + ": write failed");
}

}  // namespace rastsim::sweep
