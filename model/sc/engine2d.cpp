// SPDX-License-Identifier: Apache-2.0
#include "sc/engine2d.h"

#include "sc/model_error.h"
#include "sc/rop.h"

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
      if (mem_) mem_->begin(now());
      ctx_.render.draw2d.pixels += execute_op2d(fb_, w, op, mem_ ? &mem_->functional().color : nullptr);
      const uint64_t work = p_.engine2d_op_cycles(op, w.paint.rop3);
      busy(mem_ ? mem_->transaction_cycles(work, now()) : work);
    }
    write(done_, g);
  }
}

}  // namespace rastsim::sc
