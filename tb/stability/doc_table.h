// SPDX-License-Identifier: Apache-2.0
// Reads the figures of docs/stability.md back for the stability tests: the first
// Markdown table under a "## <section>" heading, as rows of trimmed cells (header and
// separator dropped). A test compares what its search finds with the row the doc gives,
// so the doc and the model cannot drift apart silently.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rastsim::testing {

inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

using DocRow = std::vector<std::string>;

// Rows of table number `index` (0: the first) of section `section` of docs/stability.md
// (cells trimmed, a "\|" inside a cell kept as "|").
inline std::vector<DocRow> doc_table(const std::string& section, int index = 0) {
  const std::string path = std::string(RASTSIM_SOURCE_DIR) + "/docs/stability.md";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  bool in_section = false, in_table = false;
  int table_line = 0, tables_seen = 0;
  std::vector<DocRow> rows;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      if (in_section) break;
      in_section = trim(line.substr(3)) == section;
      continue;
    }
    if (!in_section) continue;
    if (line.rfind("|", 0) != 0) {
      if (in_table && tables_seen++ == index) break;  // the end of the wanted table
      in_table = false;
      table_line = 0;
      continue;
    }
    in_table = true;
    if (tables_seen != index) continue;
    if (table_line++ < 2) continue;  // header and |---| separator
    DocRow row;
    std::string cell;
    for (size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') { cell += '|'; ++i; continue; }
      if (line[i] == '|') { row.push_back(trim(cell)); cell.clear(); continue; }
      cell += line[i];
    }
    rows.push_back(row);
  }
  if (rows.empty())
    throw std::runtime_error(path + ": no table " + std::to_string(index) + " in section \"" + section + "\"");
  return rows;
}

// The row whose first cell is `key` in table `index` of the section; throws when none.
inline DocRow doc_row(const std::string& section, const std::string& key, int index = 0) {
  for (const DocRow& r : doc_table(section, index))
    if (!r.empty() && r[0] == key) return r;
  throw std::runtime_error("docs/stability.md, \"" + section + "\": no row \"" + key + "\"");
}

}  // namespace rastsim::testing
