// SPDX-License-Identifier: Apache-2.0
// 2D front end: the line, point and shape stage beside the triangle path. Turns one 2D
// command into the 2D engine's operations (ref/2d/draw2d.h: draw2d_ops): spans of points,
// rectangles, filled circles and polygons; pixel streams of diamond and DDA lines and of
// outlines; whole index-method lines for the engine's line unit; clipped blits.
//
// - Command fetch hands it each 2D command with the raster state (viewport, scissor) as
//   it stands at that command in program order.
// - Cost: setup2d.ops_per_cycle operations a cycle, at least 1 cycle a command
//   (TimingParams::setup2d_cycles).
// - Counts primitives_2d and primitives_2d_culled.
#pragma once

#include <memory>

#include "ref/2d/draw2d.h"
#include "sc/stage.h"
#include "config/timing_params.h"

namespace rastsim::sc {

struct Draw2dJob {
  CommandPtr cmd;                              // a CmdDraw2d
  std::shared_ptr<const RasterState> state;    // the state it is drawn with
};
using Draw2dItem = Item<Draw2dJob>;

struct Op2dBatch {
  CommandPtr cmd;
  std::shared_ptr<const Draw2dWork> work;
};
using Op2dItem = Item<Op2dBatch>;

class Draw2dSetup : public Stage {
 public:
  static constexpr StageId kId = StageId::Draw2dSetup;
  Draw2dSetup(SimContext& ctx, const TimingParams& p, Link<Draw2dItem>& in,
              Link<Op2dItem>& out,
            sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), p_(p), in_(in), out_(out) {}

 private:
  void body() override;
  const TimingParams& p_;
  Link<Draw2dItem>& in_;
  Link<Op2dItem>& out_;
};

}  // namespace rastsim::sc
