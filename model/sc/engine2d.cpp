// SPDX-License-Identifier: Apache-2.0
#include "sc/engine2d.h"

#include "sc/model_error.h"

namespace rastsim::sc {

void Engine2d::body() {
  for (;;) {
    const Op2dItem in = read(in_);
    const PortGrant g = read(grant_, false);  // one transaction a command: its operations, then the port
    if (g.cmd != in.work.cmd)
      throw ModelError(std::string(name()) + ": the ROP granted " + g.cmd->loc.str() + " but the next 2D command is " +
                       in.work.cmd->loc.str());
    busy(TimingParams::engine2d_grant_cycles());  // taking the port
    const Draw2dWork& w = *in.work.work;
    for (const Op2d& op : w.ops) {
      ctx_.render.draw2d.pixels += execute_op2d(fb_, w, op);
      busy(p_.engine2d_op_cycles(op, w.paint.rop3));
    }
    write(done_, g);
  }
}

}  // namespace rastsim::sc
