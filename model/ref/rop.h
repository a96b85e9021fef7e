// SPDX-License-Identifier: Apache-2.0
// ROP: depth test against the depth buffer, then colour (and depth) write.
#pragma once

#include <cstdint>
#include <cstring>
#include <utility>

#include "ref/framebuffer.h"
#include "ref/interpolate.h"
#include "ref/raster_state.h"

namespace rastsim {

// True when func(fragment_z, stored_z) passes.
inline bool depth_test(DepthFunc func, uint32_t z, uint32_t stored) {
  switch (func) {
    case DepthFunc::Never: return false;
    case DepthFunc::Less: return z < stored;
    case DepthFunc::LEqual: return z <= stored;
    case DepthFunc::Equal: return z == stored;
    case DepthFunc::Greater: return z > stored;
    case DepthFunc::GEqual: return z >= stored;
    case DepthFunc::NotEqual: return z != stored;
    case DepthFunc::Always: return true;
  }
  return false;
}

// Tests and writes one fragment; returns true when it was written (any sample). With a
// multisampled framebuffer the fragment's depth is tested against, and its colour and
// depth written to, each sample of f.mask separately; `samples_passed`, if given, counts
// the samples written. Inline: it runs once a fragment (a call was a fifth of a render
// of small triangles).
inline bool rop_write(Framebuffer& fb, const Fragment& f, DepthFunc func, bool depth_write,
                      uint64_t* samples_passed = nullptr) {
  uint32_t n = 0;
  const int samples = fb.samples;
  const uint32_t mask = samples == 1 ? 1u : f.mask;
  for (int s = 0; s < samples; ++s) {
    if (!((mask >> s) & 1)) continue;
    if (!depth_test(func, f.z, std::as_const(fb).depth_at(f.x, f.y, s))) continue;
    if (depth_write) fb.set_depth(f.x, f.y, s, f.z);
    const uint8_t rgba[4] = {f.r, f.g, f.b, 255};
    std::memcpy(fb.sample(f.x, f.y, s), rgba, 4);
    ++n;
  }
  if (samples_passed) *samples_passed += n;
  return n > 0;
}

}  // namespace rastsim
