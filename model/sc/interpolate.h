// SPDX-License-Identifier: Apache-2.0
// Attribute interpolation: colour and depth of each covered pixel (ref/interpolate.h:
// shade_pixel), a tile's batch at a time.
//
// - Each pixel gives its fragments by shade_pixel: one (one sample, or msaa: centre-
//   shaded, carrying the pixel's mask), or one per covered sample (ssaa).
// - A batch shading N fragments takes ceil(N / interp.fragments_per_cycle) cycles; its
//   fragments are ready for the ROP interp.latency_cycles later (divider pipeline).
// - Counts fragments_shaded.
// - Every fragment leaving here goes to the fragment sink, in order: the same stream
//   (ref/pipeline.h: fragment_trace_line) as the reference model's.
#pragma once

#include <vector>

#include "ref/interpolate.h"
#include "sc/fine_raster.h"
#include "sc/recycler.h"

namespace rastsim::sc {

using FragmentItem = Item<std::shared_ptr<const std::vector<Fragment>>>;

class Interpolate : public Stage {
 public:
  Interpolate(sc_core::sc_module_name name, SimContext& ctx, const RasterState& arch, const TimingParams& p,
              Link<PixelItem>& in, Link<FragmentItem>& out)
      : Stage(name, ctx, 5), frac_bits_(arch.coord_format.frac_bits), p_(p), in_(in), out_(out) {}

 private:
  void body() override;
  int frac_bits_;
  const TimingParams& p_;
  Link<PixelItem>& in_;
  Link<FragmentItem>& out_;
  Recycler<std::vector<Fragment>> fragments_;  // no allocation a batch (sc/recycler.h)
};

}  // namespace rastsim::sc
