// SPDX-License-Identifier: Apache-2.0
// The run's parameters for one scene: what the scene's kind changes in the raster state.
// Every command and child process that runs a scene resolves its config here, so a
// scene draws the same at every level (reference, SystemC, RTL, estimate, sweep).
#pragma once

#include <string>

#include "config/arch_params.h"

namespace rastsim {

// ArchParams::resolve(cfg), then, when `scene_path` is an OBJ mesh (is_obj_path) and
// scene.obj_depth_func is not "config", the raster state's depth test is
// scene.obj_depth_func (default "less": a mesh hides its back faces). A trace keeps
// raster.depth_func. The config itself is left as written.
ArchParams resolve_for_scene(const Config& cfg, const std::string& scene_path);

}  // namespace rastsim
