// SPDX-License-Identifier: Apache-2.0
#include "sc/front_end.h"

namespace rastsim::sc {

void FrontEnd::body() {
  for (;;) {
    const ClipCommandItem in = read(in_);
    const Command& cmd = *in.work.cmd;
    FrontEndStats& stats = ctx_.render.front_end;
    FrontEndStats last = stats;  // the counters at the last step charged
    // Each triangle out is charged what the front end did since the last one (the
    // primitives taken in, culled ones included, and the vertices clipping made) plus
    // its own vertices, then written, so its cycles fall between its neighbours'.
    front_end(std::get<CmdPrimitives>(cmd.body), *in.work.state, cmd.loc, stats, [&](const ScreenTriangle& t) {
      busy(p_.front_end_step_cycles(last, stats, true));
      last = stats;
      write(out_, ScreenItem{nullptr, ScreenTriangleOut{in.work.cmd, t}}, p_.front_end_pipeline_latency());
    });
    busy(p_.front_end_step_cycles(last, stats, false));  // the primitives after the last triangle
    write(out_, ScreenItem{nullptr, ScreenTriangleOut{in.work.cmd, std::nullopt}}, p_.front_end_pipeline_latency());
  }
}

}  // namespace rastsim::sc
