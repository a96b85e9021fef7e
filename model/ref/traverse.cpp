// SPDX-License-Identifier: Apache-2.0
#include "ref/traverse.h"

#include <sstream>

namespace rastsim {

const char* to_string(Traversal m) {
  switch (m) {
    case Traversal::Tiled: return "tiled";
    case Traversal::Bbox: return "bbox";
    case Traversal::Hierarchical: return "hierarchical";
    case Traversal::Scanline: return "scanline";
  }
  return "?";
}

std::vector<int> parse_hier_levels(const std::string& text) {
  std::vector<int> levels;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, '/');) {
    if (item.empty() || item.size() > 4 || item.find_first_not_of("0123456789") != std::string::npos) return {};
    const int n = std::stoi(item);
    const bool pow2 = n >= 2 && n <= 1024 && (n & (n - 1)) == 0;
    if (!pow2 || (!levels.empty() && n >= levels.back())) return {};
    levels.push_back(n);
  }
  if (levels.empty() || levels.size() > 8 || (!text.empty() && text.back() == '/')) return {};
  return levels;
}

}  // namespace rastsim
