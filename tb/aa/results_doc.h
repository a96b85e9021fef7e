// SPDX-License-Identifier: Apache-2.0
// The coverage-error table of docs/results.md, read back for the tests: the first
// Markdown table after the heading "## Anti-aliasing: coverage error" (any level), each
// row as a map from the header's column names to the trimmed cells. Changing a figure
// therefore means changing the doc.
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rastsim::aa_test {

using TableRow = std::map<std::string, std::string>;

inline std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  std::getline(in, cell, '|');  // before the leading bar
  while (std::getline(in, cell, '|')) {
    const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!cells.empty() && cells.back().empty() && line.back() == '|') cells.pop_back();
  return cells;
}

inline std::vector<TableRow> results_table(const std::string& heading) {
  const std::string path = std::string(RASTSIM_SOURCE_DIR) + "/docs/results.md";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  bool found = false;
  while (!found && std::getline(in, line))
    found = line.starts_with("#") && line.find_first_not_of('#') != std::string::npos &&
            line.substr(line.find_first_not_of("# ")) == heading;
  if (!found) throw std::runtime_error(path + ": no heading \"" + heading + "\"");
  std::vector<std::string> header;
  std::vector<TableRow> rows;
  while (std::getline(in, line)) {
    if (line.starts_with("#")) break;  // the next section: the table must come before it
    if (!line.starts_with("|")) {
      if (!rows.empty()) break;
      continue;
    }
    if (header.empty()) {
      header = split_cells(line);
      continue;
    }
    if (line.find("---") != std::string::npos) continue;
    const std::vector<std::string> cells = split_cells(line);
    if (cells.size() != header.size()) throw std::runtime_error(path + ": ragged row: " + line);
    TableRow row;
    for (size_t i = 0; i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  if (rows.empty()) throw std::runtime_error(path + ": no table under \"" + heading + "\"");
  return rows;
}

}  // namespace rastsim::aa_test
