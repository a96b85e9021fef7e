// SPDX-License-Identifier: Apache-2.0
// Command fetch: reads the scene as a command stream.
//
// - A state command (viewport, scissor, clear, clear depth) is one transaction.
// - A primitive command (list, strip, fan) is streamed one triangle at a time: each
//   transaction names the command and the triangle index, so assembly can start on the
//   first triangle while the rest of the vertices are still being fetched.
// - A 2D command goes two ways: whole to the 2D front end, with the raster state it is
//   drawn with (fetch keeps a copy, updated by viewport and scissor commands in program
//   order), and as a marker down the triangle path, where it keeps its place in program
//   order until the ROP hands its port to the 2D engine (sc/engine2d.h).
// - Cost: fetch.cycles_per_command for a command header, plus ceil(new vertices /
//   fetch.vertices_per_cycle) per triangle (3 new vertices in a list, 1 in a strip or
//   fan after its first triangle); a 2D command its header plus ceil(vertices /
//   fetch.vertices_per_cycle).
// - A clip-space command (tri4, v4 blocks) goes whole to the geometry front end
//   (sc/front_end.h), with the raster state it is drawn with, and as a marker down the
//   triangle path, where primitive assembly takes the front end's triangles in its place.
//   Cost: its header plus ceil(vertices / fetch.vertices_per_cycle), as a 2D command.
// - The commands come from a CommandSource, in program order: a whole Scene's
//   (scene_source), or a trace streamed batch by batch while the simulation runs
//   (stream_source; the parser runs on fetch's own thread, so a malformed line late in
//   the file stops the simulation there with its SceneError). Stages hold CommandPtrs
//   (sim_context.h), which keep a streamed batch alive while any transaction names it.
// - With raster.samples > 1, after the last command: the end-of-frame marker
//   (SimContext::end_of_frame), one command header, down the triangle path; a 2D
//   command is an error there (check_2d_sample_count).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "ref/framebuffer.h"
#include "ref/scene.h"
#include "sc/draw2d_setup.h"
#include "sc/front_end.h"
#include "sc/stage.h"
#include "config/timing_params.h"

namespace rastsim::sc {

struct TriangleRef {
  CommandPtr cmd;     // a primitives command
  size_t index = 0;   // triangle index within it (a clip-space command's marker: 0)
};
using CommandItem = Item<TriangleRef>;

// Calls `take` once per command, in program order (and may throw SceneError midway).
using CommandTake = std::function<void(CommandPtr)>;
using CommandSource = std::function<void(const CommandTake& take)>;
// A whole scene's commands, borrowed: `scene` must outlive the simulation.
CommandSource scene_source(const Scene& scene);

class CommandFetch : public Stage {
 public:
  static constexpr StageId kId = StageId::CommandFetch;
  CommandFetch(SimContext& ctx, CommandSource source, const RasterState& arch,
               const TimingParams& p, Link<CommandItem>& out, Link<ClipCommandItem>& out_clip,
               Link<Draw2dItem>& out_2d, sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), source_(std::move(source)), st_(arch), p_(p), out_(out), out_clip_(out_clip),
        out_2d_(out_2d) {
    set_stack_size(kStackBytes);  // a streamed source's parser runs on this thread
  }

 private:
  static constexpr size_t kStackBytes = size_t(1) << 20;
  void body() override;
  void fetch(const CommandPtr& cmd);
  CommandSource source_;
  RasterState st_;     // the state 2D and clip-space commands are drawn with
  Framebuffer no_fb_;  // fetch owns no pixels: clears pass through to the ROP
  const TimingParams& p_;
  Link<CommandItem>& out_;
  Link<ClipCommandItem>& out_clip_;
  Link<Draw2dItem>& out_2d_;
};

}  // namespace rastsim::sc
