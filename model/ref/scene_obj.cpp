// SPDX-License-Identifier: Apache-2.0
// STUB: replaced by the OBJ parser.
#include "scene.h"
namespace rastsim {
Scene parse_obj(const std::string&, const std::string& name, const ObjPlacement&, const std::string&) { throw SceneError(name + ": OBJ parser not built yet"); }
Scene load_obj(const std::string& path, const ObjPlacement& p) { return parse_obj("", path, p, "."); }
}  // namespace rastsim
