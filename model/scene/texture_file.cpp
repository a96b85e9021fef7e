// SPDX-License-Identifier: Apache-2.0
#include "scene/texture_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "ref/scene.h"
#include "scene/stb_image_impl.h"
#include "scene/scene_text.h"

namespace rastsim {

namespace {

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// stb_image reads an uncompressed TGA past a short file's end as zeros: its size is
// checked here (header 18 bytes, the image ID, the colour map, then the pixels).
bool tga_truncated(const std::vector<uint8_t>& b) {
  if (b.size() < 18) return false;  // stb_image rejects it
  const unsigned id = b[0], cmap_type = b[1], type = b[2];
  if (type != 1 && type != 2 && type != 3) return false;  // run-length types: stb_image's checks
  const uint64_t cmap_len = cmap_type ? (uint64_t(b[5]) | uint64_t(b[6]) << 8) * ((b[7] + 7u) / 8u) : 0;
  const uint64_t w = uint64_t(b[12]) | uint64_t(b[13]) << 8, h = uint64_t(b[14]) | uint64_t(b[15]) << 8;
  return b.size() < 18 + id + cmap_len + w * h * ((b[16] + 7u) / 8u);
}

}  // namespace

std::shared_ptr<const TextureImage> load_texture_file(const std::string& path, const std::string& file, int line) {
  const auto fail = [&](const std::string& why) {
    scene_text::fail(file, line, "texture " + scene_text::quote(path) + ": " + why);
  };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("no such file");
  if (std::filesystem::file_size(path, ec) > kMaxTextureFileBytes)
    fail("larger than " + std::to_string(kMaxTextureFileBytes) + " bytes");
  const std::vector<uint8_t> bytes = read_bytes(path);
  if (bytes.empty()) fail("empty file (not a PNG, TGA or JPEG image)");
  if (tga_truncated(bytes)) fail("truncated TGA (the file ends before its last pixel)");
  int w = 0, h = 0, n = 0;
  const DecodedImage img = decode_rgba8(bytes, w, h, n);
  if (!img.pixels) fail(std::string("not a readable PNG, TGA or JPEG image (") + img.reason + ")");
  if (w > kMaxTextureExtent || h > kMaxTextureExtent)
    fail(std::to_string(w) + " x " + std::to_string(h) + " texels: a side is above " +
         std::to_string(kMaxTextureExtent));
  auto t = std::make_shared<TextureImage>();
  t->name = path;
  t->width = w;
  t->height = h;
  t->rgba.assign(img.pixels.get(), img.pixels.get() + size_t(w) * size_t(h) * 4);
  return t;
}

}  // namespace rastsim
