// SPDX-License-Identifier: Apache-2.0
// The one translation unit that compiles stb_image (stb_image_impl.cpp, its warnings
// silenced there alone): PNG, TGA and JPEG into RGBA8.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace rastsim {

struct DecodedImage {
  std::unique_ptr<uint8_t, void (*)(void*)> pixels{nullptr, nullptr};  // w x h x 4, or null
  const char* reason = "";  // stb_image's failure reason when pixels is null
};

// Decodes a PNG, TGA or JPEG held in `bytes` into RGBA8 (w, h, and n the file's channels).
DecodedImage decode_rgba8(const std::vector<uint8_t>& bytes, int& w, int& h, int& n);

}  // namespace rastsim
