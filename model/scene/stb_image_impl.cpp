// SPDX-License-Identifier: Apache-2.0
// stb_image's implementation, compiled once, PNG, TGA and JPEG only; the warnings of the
// third-party code are silenced for this file alone (model/scene/CMakeLists.txt).
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_TGA
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
// A header claiming more texels a side is refused before any allocation.
#include "scene/texture_file.h"
#define STBI_MAX_DIMENSIONS rastsim::kMaxTextureExtent
#include <stb_image.h>

#include "scene/stb_image_impl.h"

namespace rastsim {

DecodedImage decode_rgba8(const std::vector<uint8_t>& bytes, int& w, int& h, int& n) {
  DecodedImage d;
  stbi_uc* p = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n, 4);
  d.pixels = {p, stbi_image_free};
  if (!p) d.reason = stbi_failure_reason();
  return d;
}

}  // namespace rastsim
