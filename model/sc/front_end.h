// SPDX-License-Identifier: Apache-2.0
// The geometry front end (docs/clip-space.md): the stage beside the triangle path,
// between command fetch and primitive assembly, that clip-space commands (tri4, v4
// blocks) pass through; screen-space commands bypass it.
//
// - Command fetch hands it each clip-space command whole, with the raster state it is
//   drawn with (viewport, viewport_xform default), and sends a marker down the command
//   FIFO in its place; primitive assembly, on the marker, takes this stage's screen-space
//   triangles until the command's end (sc/prim_assembly.h). The command before its marker,
//   as a 2D command before its: assembly's wait on this stage never depends on a later
//   write of fetch (sc/link.h, wake-ups).
// - Computes with the reference's own function (ref/front_end.h: clip, divide, viewport
//   map, points and lines), counting into RenderStats::front_end.
// - Cost (TimingParams::front_end_step_cycles): each primitive's plane tests
//   (front_end.cycles_per_primitive) and the vertices clipping makes
//   (front_end.clip_cycles_per_vertex), then each triangle's new vertices through the
//   divide and viewport lanes (front_end.vertices_per_cycle), ready downstream
//   front_end.latency_cycles later. The end of a command is a transaction of no cycles.
#pragma once

#include <memory>
#include <optional>

#include "ref/front_end.h"
#include "sc/stage.h"
#include "config/timing_params.h"

namespace rastsim::sc {

struct ClipCommandJob {
  CommandPtr cmd;                            // a clip-space CmdPrimitives
  std::shared_ptr<const RasterState> state;  // the state it is drawn with
};
using ClipCommandItem = Item<ClipCommandJob>;

// One screen-space triangle of a clip-space command, or (no triangle) the command's end.
struct ScreenTriangleOut {
  CommandPtr cmd;
  std::optional<ScreenTriangle> triangle;
};
using ScreenItem = Item<ScreenTriangleOut>;

class FrontEnd : public Stage {
 public:
  static constexpr StageId kId = StageId::FrontEnd;
  FrontEnd(SimContext& ctx, const TimingParams& p, Link<ClipCommandItem>& in, Link<ScreenItem>& out,
           sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), p_(p), in_(in), out_(out) {}

 private:
  void body() override;
  const TimingParams& p_;
  Link<ClipCommandItem>& in_;
  Link<ScreenItem>& out_;
};

}  // namespace rastsim::sc
