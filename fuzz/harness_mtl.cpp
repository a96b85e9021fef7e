// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the MTL reader (ObjParser::parse_mtl in model/scene/scene_obj.cpp),
// which is reached only through an OBJ's `mtllib`. The input is the MTL file's bytes,
// written to a scratch file; a fixed one-triangle OBJ loads it and uses the first
// material it names (so a Kd is looked up), or none when it names none.
// Bad input may end only in SceneError; accepted scenes are checked by check_placed.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_obj_common.h"
#include "harness.h"

namespace {

// The name after the first `newmtl`, as the parser reads it (tokens joined by one space,
// up to a '#'), or empty.
std::string first_material(std::string_view t) {
  for (size_t b = 0; b < t.size();) {
    size_t e = t.find('\n', b);
    if (e == std::string_view::npos) e = t.size();
    std::string_view line = t.substr(b, e - b);
    line = line.substr(0, line.find('#'));
    std::string name;
    bool first = true, is_newmtl = false;
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && std::string_view(" \t\r\v\f").find(line[i]) != std::string_view::npos) ++i;
      const size_t s = i;
      while (i < line.size() && std::string_view(" \t\r\v\f").find(line[i]) == std::string_view::npos) ++i;
      if (s == i) break;
      const std::string_view tok = line.substr(s, i - s);
      if (first) is_newmtl = tok == "newmtl";
      else if (is_newmtl) name += (name.empty() ? "" : " ") + std::string(tok);
      first = false;
    }
    if (is_newmtl && !name.empty()) return name;
    b = e + 1;
  }
  return {};
}

}  // namespace

namespace rastsim::fuzz {

void mtl_one(std::string_view input) {
  const std::string_view mtl = input;
  scratch_file("fuzz.mtl", mtl);
  const std::string use = first_material(mtl);
  // A material name with a newline or NUL cannot be written on a usemtl line; skip it.
  const bool usable = !use.empty() && use.find_first_of(std::string("\n\0", 2)) == std::string::npos;
  const std::string obj = "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0 0.5 0.5 0.5\n" +
                          (usable ? "usemtl " + use + "\n" : std::string()) + "f 1 2 3\n";
  parse_and_check_obj(obj, "fuzz.obj", scratch_dir());
}

}  // namespace rastsim::fuzz
