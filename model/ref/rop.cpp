// SPDX-License-Identifier: Apache-2.0
#include "ref/rop.h"

namespace rastsim {

bool depth_test(DepthFunc func, uint32_t z, uint32_t stored) {
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

bool rop_write(Framebuffer& fb, const Fragment& f, DepthFunc func, bool depth_write, uint64_t* samples_passed) {
  uint32_t n = 0;
  const int samples = fb.samples;
  const uint32_t mask = samples == 1 ? 1u : f.mask;
  for (int s = 0; s < samples; ++s) {
    if (!((mask >> s) & 1)) continue;
    if (!depth_test(func, f.z, fb.depth_at(f.x, f.y, s))) continue;
    if (depth_write) fb.set_depth(f.x, f.y, s, f.z);
    uint8_t* p = fb.sample(f.x, f.y, s);
    p[0] = f.r;
    p[1] = f.g;
    p[2] = f.b;
    p[3] = 255;
    ++n;
  }
  if (samples_passed) *samples_passed += n;
  return n > 0;
}

}  // namespace rastsim
