// SPDX-License-Identifier: Apache-2.0
#include "scene/scene_params.h"

#include "config/raster_state_config.h"
#include "scene/scene_io.h"

namespace rastsim {

ArchParams resolve_for_scene(const Config& cfg, const std::string& scene_path) {
  ArchParams a = ArchParams::resolve(cfg);
  const std::string& obj_depth = cfg.get_string("scene.obj_depth_func");
  if (is_obj_path(scene_path) && obj_depth != "config") a.raster.depth_func = depth_func_from_name(obj_depth);
  return a;
}

}  // namespace rastsim
