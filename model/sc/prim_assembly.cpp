// SPDX-License-Identifier: Apache-2.0
#include "sc/prim_assembly.h"

#include "ref/prim_assembly.h"

namespace rastsim::sc {

void PrimAssembly::assemble(const ScreenTriangle& v, const CommandPtr& cmd) {
  busy(p_.assembly_triangle_cycles());
  write(out_, TriangleItem{nullptr, AssembledTriangle{v, cmd}});
}

void PrimAssembly::body() {
  for (;;) {
    const CommandItem in = read(in_);
    if (pass_state(in, out_)) continue;
    const auto& prims = std::get<CmdPrimitives>(in.work.cmd->body);
    if (!prims.clip_space()) {
      assemble(assemble_triangle(prims, in.work.index), in.work.cmd);
      continue;
    }
    for (;;) {  // the front end's triangles of this command, to its end
      const ScreenItem s = read(screen_in_);
      if (!s.work.triangle) break;
      assemble(*s.work.triangle, s.work.cmd);
    }
  }
}

}  // namespace rastsim::sc
