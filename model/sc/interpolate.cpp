// SPDX-License-Identifier: Apache-2.0
#include "sc/interpolate.h"

#include "ref/pipeline.h"

namespace rastsim::sc {

void Interpolate::body() {
  for (;;) {
    const PixelItem in = read(in_);
    if (pass_state(in, out_, p_.interp_pipeline_latency())) continue;
    const PixelBatch& batch = *in.work;
    const SetupTriangle& tri = *batch.tri;
    LocalPtr<FragmentBatch> frags = fragments_.take();
    frags->pixels = in.work;
    // At most one fragment a covered sample (ssaa), one a pixel otherwise.
    Fragment* const first = frags->reset(size_t(batch.pixels) * size_t(tri.samples));
    Fragment* out = first;
    if (shader_tri_ != batch.tri) {
      shader_tri_ = batch.tri;
      shader_.emplace(tri, frac_bits_);  // the reference's shading, fast path included
    }
    PixelShader& shader = *shader_;
    // Per batch, not per fragment: the stepped plane equations with no sink are the
    // common case and store fragments only, a run at a time.
    if (shader.stepped() && !ctx_.on_fragment) {
      for (const PixelRun& r : batch.runs)
        shader.shade_run(r.y, r.x0, [&](auto&& frag) {
          for (int x = r.x0; x < r.x1; ++x) *out++ = frag(x);
        });
    } else {
      const bool dda = tri.interp_method != InterpMethod::Plane;
      for (const PixelRun& r : batch.runs) {
        for (int x = r.x0; x < r.x1; ++x) {
          shader.shade(x, r.y, r.mask, [&](const Fragment& f) {
            *out++ = f;
            // interp.method = dda: its error against the plane equations, counted as the
            // reference's render_scene counts it (same stats keys at both levels).
            if (dda) count_interp_error(f, interpolate_plane(tri, x, r.y, frac_bits_), ctx_.render);
            if (ctx_.on_fragment) ctx_.on_fragment(f);
          });
        }
      }
    }
    frags->count = size_t(out - first);
    ctx_.render.fragments_shaded += frags->count;
    if (frags->count != 0) attribute_to(first->x, first->y);  // the batch's tile
    const uint64_t cycles = p_.interp_batch_cycles(frags->count, tri.affine);
    if (!tri.affine) {  // a reciprocal a fragment (docs/clip-space.md, "Timing")
      ctx_.recip_reciprocals += frags->count;
      ctx_.recip_busy_cycles += cycles;
    }
    busy(cycles);
    write(out_, FragmentItem{nullptr, std::move(frags)}, p_.interp_pipeline_latency());
  }
}

}  // namespace rastsim::sc
