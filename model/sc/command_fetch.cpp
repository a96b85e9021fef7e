// SPDX-License-Identifier: Apache-2.0
#include "sc/command_fetch.h"

#include "ref/pipeline.h"
#include "ref/prim_assembly.h"

namespace rastsim::sc {

CommandSource scene_source(const Scene& scene) {
  return [&scene](const CommandTake& take) {
    for (const Command& c : scene.commands) take(borrow_command(c));
  };
}

void CommandFetch::fetch(const CommandPtr& p) {
  const Command& cmd = *p;
  const auto mark = [&](size_t k) {
    if (ctx_.on_fetch) ctx_.on_fetch(cmd, k, now());
  };
  if (!std::holds_alternative<CmdPrimitives>(cmd.body)) mark(0);
  if (const auto* d2 = std::get_if<CmdDraw2d>(&cmd.body)) {
    check_2d_sample_count(cmd, st_);
    busy(p_.fetch_draw2d_cycles(draw2d_vertex_count(*d2)));
    // The job before its marker: once the ROP holds the marker it waits on the engine,
    // whose input must not depend on fetch's later writes (sc/link.h, wake-ups).
    write(out_2d_, Draw2dItem{nullptr, Draw2dJob{p, std::make_shared<const RasterState>(st_)}});
    write(out_, CommandItem{p, {}});
    return;
  }
  const auto* prims = std::get_if<CmdPrimitives>(&cmd.body);
  if (!prims) {
    apply_state_command(cmd, st_, no_fb_);  // viewport, scissor
    busy(p_.fetch_header_cycles());
    write(out_, CommandItem{p, {}});
    return;
  }
  const size_t n = triangle_count(*prims);
  if (n == 0) mark(0);
  if (n == 0) busy(p_.fetch_header_cycles());
  for (size_t k = 0; k < n; ++k) {
    mark(k);
    const uint64_t new_vertices = (k == 0 || prims->topology == Topology::List) ? 3 : 1;
    busy(p_.fetch_triangle_cycles(k == 0, new_vertices));
    write(out_, CommandItem{nullptr, TriangleRef{p, k}});
  }
}

void CommandFetch::body() {
  source_([&](CommandPtr cmd) {
    fetch(cmd);
    ++fetched_;
  });
  // Multisampling: the frame ends with the resolve pass, ordered after every fragment by
  // a marker fetched like a command header (sc/rop.h).
  if (st_.samples > 1) {
    busy(p_.fetch_header_cycles());
    write(out_, CommandItem{borrow_command(ctx_.end_of_frame), {}});
  }
}

}  // namespace rastsim::sc
