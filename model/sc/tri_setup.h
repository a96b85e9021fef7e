// SPDX-License-Identifier: Apache-2.0
// Triangle setup: snapping, culling, edge equations and bounding box of one triangle
// (ref/tri_setup.h: setup_triangle), pipelined.
//
// - Keeps its own copy of the raster state; viewport and scissor commands update it as
//   they pass (ref/pipeline.h: apply_state_command), in program order.
// - Cost: setup.interval_cycles per triangle (initiation interval); the set-up triangle
//   is ready for coarse raster setup.latency_cycles after it entered (latency >=
//   interval). A culled triangle costs the interval and produces nothing.
// - Counts the triangle stats of the reference model (triangles_in, culled, ...).
#pragma once

#include <deque>
#include <memory>

#include "ref/framebuffer.h"
#include "ref/raster_state.h"
#include "ref/tri_setup.h"
#include "sc/prim_assembly.h"
#include "sc/recycler.h"

namespace rastsim::sc {

using SetupItem = Item<LocalPtr<const SetupTriangle>>;

class TriSetup : public Stage {
 public:
  static constexpr StageId kId = StageId::TriSetup;
  TriSetup(SimContext& ctx, const RasterState& arch, const TimingParams& p,
           Link<TriangleItem>& in, Link<SetupItem>& out,
         sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), st_(arch), p_(p), in_(in), out_(out) {}
  // pipeline.mode = binned: each written triangle's command appended to `log` (the
  // binner's, sc/binning.h: its errors name the command).
  void log_commands(std::deque<CommandPtr>* log) { log_ = log; }

 private:
  void body() override;
  RasterState st_;
  Framebuffer no_fb_;  // setup owns no pixels: clears pass through to the ROP
  const TimingParams& p_;
  Link<TriangleItem>& in_;
  Link<SetupItem>& out_;
  Recycler<SetupTriangle> triangles_;
  std::deque<CommandPtr>* log_ = nullptr;  // no allocation a triangle (sc/recycler.h)
};

}  // namespace rastsim::sc
