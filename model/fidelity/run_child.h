// SPDX-License-Identifier: Apache-2.0
// SystemC elaborates once per process: a level that needs more than one simulation
// (the tolerance rule's sampled attempts) runs each in a forked child, which sends its
// JSON back through a pipe.
#pragma once

#include <functional>

#include <nlohmann/json.hpp>

namespace rastsim::fidelity {

// Runs fn in a forked child; returns its JSON. Throws std::runtime_error with the child's
// message when fn threw ({"error": what}) or the child died.
nlohmann::json run_in_child(const std::function<nlohmann::json()>& fn);

}  // namespace rastsim::fidelity
