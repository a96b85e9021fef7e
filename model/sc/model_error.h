// SPDX-License-Identifier: Apache-2.0
// ModelError: a fault of the timed model itself (a lost or reordered transaction, a
// transaction left in a FIFO), as opposed to bad input (SceneError). simulate_scene lets
// it through with its own type, so no caller mistakes a model bug for a bad scene.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace rastsim::sc {

struct ModelError : std::logic_error {
  using std::logic_error::logic_error;
};

// The reader of `link` expected transaction number `expected` and received `got`. The
// name is a C string: this runs on every FIFO read, and a std::string parameter cost a
// heap allocation each (names are longer than the short-string buffer).
inline void check_order(const char* link, uint64_t expected, uint64_t got) {
  if (got != expected)
    throw ModelError(std::string(link) + ": expected transaction #" + std::to_string(expected) + ", got #" +
                     std::to_string(got) + " (lost or reordered)");
}

}  // namespace rastsim::sc
