// SPDX-License-Identifier: Apache-2.0
#include "sc/draw2d_setup.h"

namespace rastsim::sc {

void Draw2dSetup::body() {
  for (;;) {
    const Draw2dItem in = read(in_);
    const Command& cmd = *in.work.cmd;
    auto work = std::make_shared<Draw2dWork>(draw2d_ops(std::get<CmdDraw2d>(cmd.body), cmd.loc, *in.work.state));
    ++(work->culled ? ctx_.render.draw2d.primitives_culled : ctx_.render.draw2d.primitives);
    busy(p_.setup2d_cycles(work->ops.size()));
    write(out_, Op2dItem{nullptr, Op2dBatch{in.work.cmd, std::move(work)}});
  }
}

}  // namespace rastsim::sc
