// SPDX-License-Identifier: Apache-2.0
#include "sc/command_fetch.h"

#include "ref/prim_assembly.h"

namespace rastsim::sc {

void CommandFetch::body() {
  for (const Command& cmd : scene_.commands) {
    const auto* prims = std::get_if<CmdPrimitives>(&cmd.body);
    if (!prims) {
      busy(p_.fetch_cycles_per_command);
      write(out_, CommandItem{&cmd, {}});
      continue;
    }
    const size_t n = triangle_count(*prims);
    if (n == 0) busy(p_.fetch_cycles_per_command);
    for (size_t k = 0; k < n; ++k) {
      const uint64_t new_vertices = (k == 0 || prims->topology == Topology::List) ? 3 : 1;
      busy(p_.fetch_triangle_cycles(k == 0, new_vertices));
      write(out_, CommandItem{nullptr, TriangleRef{&cmd, k}});
    }
  }
}

}  // namespace rastsim::sc
