// SPDX-License-Identifier: Apache-2.0
// Texture image files (PNG, TGA, JPEG) decoded by stb_image (Debian libstb-dev) into
// RGBA8, row 0 the file's top row (ref/texture/texture.h). The trace's `texture ID FILE`
// and an MTL's `map_Kd FILE` load through here.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "ref/texture/texture.h"

namespace rastsim {

// The largest texture side accepted, texels (stb_image refuses a larger header before it
// allocates), and the largest file read.
inline constexpr int kMaxTextureExtent = 16384;
inline constexpr uint64_t kMaxTextureFileBytes = uint64_t{1} << 30;

// Decodes `path`. A file that is missing, truncated or not a PNG, TGA or JPEG image, or
// larger than kMaxTextureExtent a side, throws SceneError("FILE:LINE: ...") naming
// `file`:`line`, the trace or MTL line that referred to it, and the reason.
std::shared_ptr<const TextureImage> load_texture_file(const std::string& path, const std::string& file, int line);

}  // namespace rastsim
