// SPDX-License-Identifier: Apache-2.0
#include "sc/tri_setup.h"

#include "ref/pipeline.h"

namespace rastsim::sc {

void TriSetup::body() {
  for (;;) {
    const TriangleItem in = read(in_);
    if (in.state && !ctx_.is_end_of_frame(in.state)) apply_state_command(*in.state, st_, no_fb_);  // viewport, scissor
    if (pass_state(in, out_, p_.setup_pipeline_latency())) continue;
    ++ctx_.render.triangles_in;
    LocalPtr<SetupTriangle> tri = triangles_.take();
    *tri = SetupTriangle{};  // setup_triangle fills a fresh one
    const SetupOutcome outcome = setup_triangle(in.work.v, st_, in.work.cmd->loc, *tri);
    if (const auto* prims = std::get_if<CmdPrimitives>(&in.work.cmd->body)) tri->texture = prims->texture;
    busy(p_.setup_triangle_cycles());
    if (!count_setup_outcome(outcome, ctx_.render)) continue;
    if (log_) log_->push_back(in.work.cmd);
    write(out_, SetupItem{nullptr, std::move(tri)}, p_.setup_pipeline_latency());
  }
}

}  // namespace rastsim::sc
