// SPDX-License-Identifier: Apache-2.0
#include "sc/interpolate.h"

#include "ref/pipeline.h"

namespace rastsim::sc {

void Interpolate::body() {
  for (;;) {
    const PixelItem in = read(in_);
    if (pass_state(in, out_, p_.interp_latency)) continue;
    const PixelBatch& batch = *in.work;
    std::shared_ptr<std::vector<Fragment>> frags = fragments_.take();
    frags->clear();  // keeps its capacity
    frags->reserve(batch.pixels.size());
    PixelShader shader(*batch.tri, frac_bits_);  // the reference's shading, fast path included
    // Per batch, not per fragment: the plain loop (plane equations, no sink) is the
    // common case and stores fragments only.
    const bool dda = batch.tri->interp_method != InterpMethod::Plane;
    if (!dda && !ctx_.on_fragment) {
      for (const Pixel& px : batch.pixels) shader.shade(px.x, px.y, px.mask, [&](const Fragment& f) { frags->push_back(f); });
    } else {
      for (const Pixel& px : batch.pixels) {
        shader.shade(px.x, px.y, px.mask, [&](const Fragment& f) {
          frags->push_back(f);
          // interp.method = dda: its error against the plane equations, counted as the
          // reference's render_scene counts it (same stats keys at both levels).
          if (dda) count_interp_error(f, interpolate_plane(*batch.tri, px.x, px.y, frac_bits_), ctx_.render);
          if (ctx_.on_fragment) ctx_.on_fragment(f);
        });
      }
    }
    ctx_.render.fragments_shaded += frags->size();
    if (!frags->empty()) attribute_to(frags->front().x, frags->front().y);  // the batch's tile
    busy(p_.interp_batch_cycles(frags->size()));
    write(out_, FragmentItem{nullptr, std::move(frags)}, p_.interp_latency);
  }
}

}  // namespace rastsim::sc
