// SPDX-License-Identifier: Apache-2.0
// The OBJ perspective camera (obj_camera.h): a standard perspective projection with
// the eye on the view axis, in double, rounded once a coordinate to binary32.
#include "scene/obj_camera.h"

#include <cmath>
#include <numbers>

namespace rastsim {

PerspectiveCamera::PerspectiveCamera(const ObjPlacement& pl) {
  const double f = 1.0 / std::tan(pl.fov_deg * std::numbers::pi / 360.0);  // cot(fov / 2)
  const double aspect = double(pl.viewport_width) / double(pl.viewport_height);
  x_scale_ = f / aspect;
  y_scale_ = -f;  // view +y is up, clip y = -w is the top row
  z_scale_ = pl.far / (pl.far - pl.near);
  z_offset_ = -(pl.far * pl.near) / (pl.far - pl.near);
  eye_ = pl.distance;
}

// Eye space e = (x, y, z - distance) looking along -z; w_c = -e_z = distance - z, the
// distance in front of the eye, so z_c / w_c is 0 at the near plane and 1 at the far one.
ClipVertex PerspectiveCamera::clip(const std::array<double, 3>& q) const {
  const double w = eye_ - q[2];
  ClipVertex v;
  v.x = static_cast<float>(x_scale_ * q[0]);
  v.y = static_cast<float>(y_scale_ * q[1]);
  v.z = static_cast<float>(z_scale_ * w + z_offset_);
  v.w = static_cast<float>(w);
  return v;
}

}  // namespace rastsim
