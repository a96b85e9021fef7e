// SPDX-License-Identifier: Apache-2.0
// stb_image_write (libstb-dev), compiled once for the tests' JPEG fixture; its warnings
// are silenced for this file alone (tb/texture/CMakeLists.txt).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

#include <string>
#include <vector>

namespace rastsim::texture_test {

// A JPEG (quality 100) of w x h RGB8 pixels, as bytes.
std::string jpeg_bytes(int w, int h, const std::vector<unsigned char>& rgb) {
  std::string out;
  stbi_write_jpg_to_func(
      [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), size_t(size)); },
      &out, w, h, 3, rgb.data(), 100);
  return out;
}

}  // namespace rastsim::texture_test
