// SPDX-License-Identifier: Apache-2.0
// 2D engine: executes the 2D front end's operations (spans, pixel streams, index-method
// lines through its line unit, blits) with the pattern and ROP3 on the framebuffer
// (ref/2d/draw2d.h: execute_op2d), through the ROP's framebuffer port.
//
// - Program order with the triangles: command fetch also sends each 2D command down the
//   triangle path as a marker. When the marker reaches the ROP (every fragment before it
//   written), the ROP grants its port to the engine and holds until the engine reports
//   the command done; the engine meanwhile may already hold the command's operations.
// - Cost: 1 cycle to take the port, then per operation TimingParams::engine2d_op_cycles
//   (docs/2d.md, "Timing"); the RTL (rtl/rast_engine2d.sv) takes its first operation in
//   that cycle.
// - With the timed memory system (attach_memory): the pixels' accesses go through the
//   ROP's colour client (ref/2d/raster2d.h says which), and an operation is a
//   transaction: its cycles above, or until its last line fill has arrived plus one.
// - Counts pixels_2d.
#pragma once

#include "ref/framebuffer.h"
#include "sc/draw2d_setup.h"

namespace rastsim {
class RopMemoryPort;
}  // namespace rastsim

namespace rastsim::sc {

// ROP -> engine: the port is yours for this command; engine -> ROP: it is done.
struct PortGrant {
  CommandPtr cmd;
};

class Engine2d : public Stage {
 public:
  static constexpr StageId kId = StageId::Engine2d;
  Engine2d(SimContext& ctx, const TimingParams& p, Framebuffer& fb,
           Link<Op2dItem>& in, Link<PortGrant>& grant, Link<PortGrant>& done,
         sc_core::sc_module_name name = stage_name(kId).data())
      : Stage(name, ctx, kId), p_(p), fb_(fb), in_(in), grant_(grant), done_(done) {}
  // Before the run: draw through the ROP's memory port (Rop::memory_port; null: none).
  void attach_memory(RopMemoryPort* mem) { mem_ = mem; }

 private:
  void body() override;
  const TimingParams& p_;
  Framebuffer& fb_;
  Link<Op2dItem>& in_;
  Link<PortGrant>& grant_;
  Link<PortGrant>& done_;
  RopMemoryPort* mem_ = nullptr;
};

}  // namespace rastsim::sc
