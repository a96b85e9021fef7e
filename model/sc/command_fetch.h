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
// - With raster.samples > 1, after the last command: the end-of-frame marker
//   (SimContext::end_of_frame), one command header, down the triangle path; a 2D
//   command is an error there (check_2d_sample_count).
#pragma once

#include <cstddef>

#include "ref/framebuffer.h"
#include "ref/scene.h"
#include "sc/draw2d_setup.h"
#include "sc/stage.h"
#include "config/timing_params.h"

namespace rastsim::sc {

struct TriangleRef {
  const Command* cmd = nullptr;  // a primitives command
  size_t index = 0;              // triangle index within it
};
using CommandItem = Item<TriangleRef>;

class CommandFetch : public Stage {
 public:
  CommandFetch(sc_core::sc_module_name name, SimContext& ctx, const Scene& scene, const RasterState& arch,
               const TimingParams& p, Link<CommandItem>& out, Link<Draw2dItem>& out_2d)
      : Stage(name, ctx, 0), scene_(scene), st_(arch), p_(p), out_(out), out_2d_(out_2d) {}

 private:
  void body() override;
  const Scene& scene_;
  RasterState st_;     // the state 2D commands are drawn with
  Framebuffer no_fb_;  // fetch owns no pixels: clears pass through to the ROP
  const TimingParams& p_;
  Link<CommandItem>& out_;
  Link<Draw2dItem>& out_2d_;
};

}  // namespace rastsim::sc
