// SPDX-License-Identifier: Apache-2.0
// The OBJ perspective camera (scene.camera = "perspective"; docs/trace-format.md,
// "Perspective camera"): a view-space position of the placed mesh (its bounding sphere
// the unit sphere about the origin, the viewer on +z looking along -z) to clip space in
// the convention of docs/clip-space.md (Vulkan's: y down, 0 <= z <= w).
#pragma once

#include <array>

#include "config/obj_placement.h"
#include "ref/scene.h"

namespace rastsim {

class PerspectiveCamera {
 public:
  // From scene.fov_deg, scene.near, scene.far, scene.distance and the viewport's aspect.
  explicit PerspectiveCamera(const ObjPlacement& pl);
  // The clip-space position of view-space q: each of x, y, z, w computed in double as
  // the docs state, then rounded once to binary32 (nearest even). Colour and texture
  // coordinate are left at ClipVertex's defaults.
  ClipVertex clip(const std::array<double, 3>& q) const;

 private:
  double x_scale_ = 0, y_scale_ = 0;  // f / aspect and -f, f = 1 / tan(fov / 2)
  double z_scale_ = 0, z_offset_ = 0;  // z_c = z_scale w_c + z_offset: F / (F - N), -F N / (F - N)
  double eye_ = 0;                     // the eye at view z = distance
};

}  // namespace rastsim
