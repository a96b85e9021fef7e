// SPDX-License-Identifier: Apache-2.0
// STUB: replaced by the trace parser.
#include "scene.h"
namespace rastsim {
Scene parse_trace(const std::string&, const std::string& name) { throw SceneError(name + ": trace parser not built yet"); }
Scene load_trace(const std::string& path) { return parse_trace("", path); }
Scene load_scene(const std::string& path, const ObjPlacement& p) {
  if (path.size() > 4 && path.substr(path.size() - 4) == ".obj") return load_obj(path, p);
  return load_trace(path);
}
}  // namespace rastsim
