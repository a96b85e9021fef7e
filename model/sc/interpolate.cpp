// SPDX-License-Identifier: Apache-2.0
#include "sc/interpolate.h"

namespace rastsim::sc {

void Interpolate::body() {
  for (;;) {
    const PixelItem in = read(in_);
    if (pass_state(in, out_, p_.interp_latency)) continue;
    const PixelBatch& batch = *in.work;
    auto frags = std::make_shared<std::vector<Fragment>>();
    frags->reserve(batch.pixels.size());
    for (const Pixel& px : batch.pixels) {
      frags->push_back(interpolate(*batch.tri, px.x, px.y, frac_bits_));
      if (ctx_.on_fragment) ctx_.on_fragment(frags->back());
    }
    busy(ceil_div(frags->size(), p_.interp_fragments_per_cycle));
    write(out_, FragmentItem{nullptr, std::move(frags)}, p_.interp_latency);
  }
}

}  // namespace rastsim::sc
