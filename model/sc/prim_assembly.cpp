// SPDX-License-Identifier: Apache-2.0
#include "sc/prim_assembly.h"

#include "ref/prim_assembly.h"

namespace rastsim::sc {

void PrimAssembly::body() {
  for (;;) {
    const CommandItem in = read(in_);
    if (pass_state(in, out_)) continue;
    const auto& prims = std::get<CmdPrimitives>(in.work.cmd->body);
    TriangleItem out{nullptr, AssembledTriangle{in.work.screen ? *in.work.screen : assemble_triangle(prims, in.work.index),
                                                in.work.cmd}};
    busy(p_.assembly_triangle_cycles());
    write(out_, std::move(out));
  }
}

}  // namespace rastsim::sc
