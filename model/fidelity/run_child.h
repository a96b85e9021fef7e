// SPDX-License-Identifier: Apache-2.0
// SystemC elaborates once per process: a level that needs more than one simulation
// (the tolerance rule's sampled attempts) runs each in a forked child, which sends its
// JSON back through a pipe. The SystemC tests (tb/sc/sim_harness.h, run_isolated) use the
// same code.
#pragma once

#include <functional>

#include <nlohmann/json.hpp>

namespace rastsim::fidelity {

// Runs fn in a forked child (stdout and stdio flushed first, so the child repeats no
// buffered output); returns its JSON, or {"error": what} if fn threw or the child died.
nlohmann::json run_in_child_or_error(const std::function<nlohmann::json()>& fn);

// As run_in_child_or_error, but throws std::runtime_error with the child's message.
nlohmann::json run_in_child(const std::function<nlohmann::json()>& fn);

}  // namespace rastsim::fidelity
