// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the OBJ parser and placement (model/scene/scene_obj.cpp). The input
// is an OBJ file's text; `mtllib` finds the test materials of tb/data (cube.mtl, bad_kd.mtl)
// beside it. Bad input may end only in SceneError; accepted meshes are checked by
// check_placed, and every number the OBJ reader accepts against strtod.
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_obj_common.h"
#include "harness.h"
#include "scene/scene_text.h"

namespace rastsim::fuzz {
namespace {

// OBJ numbers go through scene_text::parse_double (std::from_chars): every token it
// accepts must read as the value the C library's strtod gives for the same text.
void check_numbers(std::string_view text) {
  for_each_token(text, " \t\r\v\f\n/", [](const std::string& tok) {  // '/' splits face indices
    const auto v = scene_text::parse_double(tok);
    if (!v) return;
    const double want = std::strtod(tok.c_str(), nullptr);
    check(*v == want, "'" + tok + "' reads as " + std::to_string(*v) + ", strtod gives " + std::to_string(want));
  });
}

}  // namespace

void obj_one(std::string_view input) {
  const std::string text(input);
  check_numbers(text);
  rastsim::fuzz::parse_and_check_obj(text, "fuzz.obj", RASTSIM_FUZZ_MTL_DIR);
}

}  // namespace rastsim::fuzz
