// SPDX-License-Identifier: Apache-2.0
#include "fidelity/run_child.h"

#include <stdexcept>
#include <string>

#include "util/process.h"

namespace rastsim::fidelity {

nlohmann::json run_in_child_or_error(const std::function<nlohmann::json()>& fn) {
  ForkedResult r;
  try {
    r = run_forked([&]() -> std::string {
      try {
        return fn().dump();
      } catch (const std::exception& e) {
        return nlohmann::json{{"error", e.what()}}.dump();
      }
    });
  } catch (const std::exception& e) {
    return {{"error", e.what()}};  // no pipe or no fork
  }
  if (r.status != 0 || r.out.empty())
    return {{"error", "simulation child died (status " + std::to_string(r.status) + ")"}};
  return nlohmann::json::parse(r.out);
}

nlohmann::json run_in_child(const std::function<nlohmann::json()>& fn) {
  nlohmann::json j = run_in_child_or_error(fn);
  if (j.is_object() && j.contains("error")) throw std::runtime_error(j["error"].get<std::string>());
  return j;
}

}  // namespace rastsim::fidelity
