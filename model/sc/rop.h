// SPDX-License-Identifier: Apache-2.0
// ROP: depth test and colour/depth write of each fragment (ref/rop.h: rop_write), and
// the clears, in program order (ref/pipeline.h: apply_state_command). Owns the
// framebuffer.
//
// - A batch of N fragments takes ceil(N / rop.pixels_per_cycle) cycles.
// - A colour or depth clear takes ceil(W * H / rop.clear_pixels_per_cycle) cycles for
//   the W x H framebuffer; viewport and scissor commands 1 cycle.
// - A 2D command's marker: the ROP grants its framebuffer port to the 2D engine and
//   holds until the engine is done (sc/engine2d.h), then 1 cycle.
// - Counts fragments_passed.
#pragma once

#include "ref/framebuffer.h"
#include "sc/engine2d.h"
#include "sc/interpolate.h"

namespace rastsim::sc {

class Rop : public Stage {
 public:
  Rop(sc_core::sc_module_name name, SimContext& ctx, const RasterState& arch, const TimingParams& p,
      Link<FragmentItem>& in, Link<PortGrant>& grant_2d, Link<PortGrant>& done_2d);
  Framebuffer& framebuffer() { return fb_; }

 private:
  void body() override;
  RasterState st_;
  Framebuffer fb_;
  const TimingParams& p_;
  Link<FragmentItem>& in_;
  Link<PortGrant>& grant_2d_;
  Link<PortGrant>& done_2d_;
};

}  // namespace rastsim::sc
