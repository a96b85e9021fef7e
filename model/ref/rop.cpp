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

bool rop_write(Framebuffer& fb, const Fragment& f, DepthFunc func, bool depth_write) {
  uint32_t& stored = fb.depth[size_t(f.y) * fb.width + f.x];
  if (!depth_test(func, f.z, stored)) return false;
  if (depth_write) stored = f.z;
  uint8_t* p = fb.pixel(f.x, f.y);
  p[0] = f.r;
  p[1] = f.g;
  p[2] = f.b;
  p[3] = 255;
  return true;
}

}  // namespace rastsim
