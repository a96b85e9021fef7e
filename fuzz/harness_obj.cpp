// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the OBJ parser and placement (model/scene/scene_obj.cpp). The input
// is an OBJ file's text; `mtllib` finds the test materials of tb/data (cube.mtl, bad_kd.mtl)
// beside it. Bad input may end only in SceneError; accepted meshes are checked by check_placed.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_obj_common.h"
#include "harness.h"

namespace rastsim::fuzz {

void obj_one(std::string_view input) {
  const std::string text(input);
  rastsim::fuzz::parse_and_check_obj(text, "fuzz.obj", RASTSIM_FUZZ_MTL_DIR);
}

}  // namespace rastsim::fuzz
