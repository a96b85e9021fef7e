// SPDX-License-Identifier: Apache-2.0
#include "sc/command_fetch.h"

#include "ref/binning.h"
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
  if (st_.bin.mode == PipelineMode::Binned) check_binned_command(cmd, st_);  // not yet binned: refused
  const auto mark = [&](size_t k) {
    if (ctx_.on_fetch) ctx_.on_fetch(cmd, k, now());
  };
  // A state command: one header, then down the triangle path to the ROP.
  const auto state = [&] {
    mark(0);
    apply_state_command(cmd, st_, no_fb_);  // viewport, scissor
    busy(p_.fetch_header_cycles());
    write(out_, CommandItem{p, {}});
  };
  visit_command(cmd, Overloaded{
      state_commands(state),
      [&](const CmdPrimitives& prims) {
        if (prims.texture.enabled())  // before its first fill (sc/sim_context.h)
          ctx_.memory_time_order = ctx_.wake_writers_at_free_slot = true;
        if (prims.clip_space()) {
          // Whole to the geometry front end, then its marker (the job first: sc/front_end.h).
          mark(0);
          busy(p_.fetch_whole_command_cycles(prims.clip_vertices.size()));
          write(out_clip_, ClipCommandItem{nullptr, ClipCommandJob{p, std::make_shared<const RasterState>(st_)}});
          write(out_, CommandItem{nullptr, TriangleRef{p, 0}});
          return;
        }
        // Triangle k down to primitive assembly.
        const size_t n = triangle_count(prims);
        for (size_t k = 0; k < n; ++k) {
          mark(k);
          const uint64_t new_vertices = (k == 0 || prims.topology == Topology::List) ? 3 : 1;
          busy(p_.fetch_triangle_cycles(k == 0, new_vertices));
          write(out_, CommandItem{nullptr, TriangleRef{p, k}});
        }
        if (n == 0) {  // no triangle: the command header alone
          mark(0);
          busy(p_.fetch_header_cycles());
        }
      },
      [&](const CmdDraw2d& d2) {
        mark(0);
        check_2d_sample_count(cmd, st_);
        busy(p_.fetch_draw2d_cycles(draw2d_vertex_count(d2)));
        // The job before its marker: once the ROP holds the marker it waits on the engine,
        // whose input must not depend on fetch's later writes (sc/link.h, wake-ups).
        write(out_2d_, Draw2dItem{nullptr, Draw2dJob{p, std::make_shared<const RasterState>(st_)}});
        write(out_, CommandItem{p, {}});
      },
  });
}

void CommandFetch::body() {
  source_([&](CommandPtr cmd) { fetch(cmd); });
  // Multisampling: the frame ends with the resolve pass, ordered after every fragment by
  // a marker fetched like a command header (sc/rop.h).
  // Binned mode: the marker also ends the binning pass (sc/binning.h).
  if (st_.samples > 1 || st_.bin.mode == PipelineMode::Binned) {
    busy(p_.fetch_header_cycles());
    write(out_, CommandItem{borrow_command(ctx_.end_of_frame), {}});
  }
}

}  // namespace rastsim::sc
