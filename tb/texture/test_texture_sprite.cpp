// SPDX-License-Identifier: Apache-2.0
// Textured point sprites (docs/texture.md, "Point sprites"; docs/clip-space.md): a 3D point
// of point_size 4 with `point_sprite on` is a 4 x 4-pixel square whose s, t run from (0, 0)
// at its top-left corner to (1, 1) at its bottom-right; sampled nearest from a 4 x 4
// texture it reproduces the texture texel for texel (ctest -L texture).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

// Texel (i, j) of the 4 x 4 texture: every texel a different colour.
std::array<uint8_t, 3> sprite_texel(int i, int j) {
  return {uint8_t(60 * i + 10), uint8_t(60 * j + 20), uint8_t(13 * (i + 4 * j))};
}

// An uncompressed 32-bit TGA (top-left origin) of the 4 x 4 texture above.
std::string sprite_tga() {
  std::string b = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 4, 0, 32, 0x28};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const auto c = sprite_texel(i, j);
      b += {char(c[2]), char(c[1]), char(c[0]), char(255)};
    }
  return b;
}

// The sprite centred on the pixel corner (10, 10) of a 64 x 64 viewport: NDC
// 2 * 10 / 64 - 1 = -0.6875 on both axes (Vulkan's y: NDC -1 is the top row), so its
// square is [8, 12] x [8, 12], pixels 8..11 each way. Pixel (8 + i, 8 + j)'s centre is at
// s = (i + 1/2) / 4, inside texel i (a quarter of a texel from any edge), t alike.
Framebuffer render_sprite(bool sprite_on, RenderStats& st) {
  const fs::path dir = fs::temp_directory_path() / ("rastsim_sprite_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream((dir / "s.tga").string(), std::ios::binary) << sprite_tga();
  const std::string text = std::string("viewport 64 64\nclear 0 0 0\ntexture 1 s.tga\nbindtexture 1\n") +
                           "texfilter nearest\ntexenv replace\npoint_size 4\npoint_sprite " +
                           (sprite_on ? "on" : "off") + "\ntexcoord 0.6 0.1\npoints\nv4 -0.6875 -0.6875 0.5 1\nend\n";
  const Scene sc = parse_trace(text, (dir / "t.trace").string());
  fs::remove_all(dir);
  return render_scene(sc, raster_state_from_config(Config{}), st);
}

TEST(TextureSprite, PointSpriteReproducesTheTexture) {
  RenderStats st;
  const Framebuffer fb = render_sprite(true, st);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint8_t* p = fb.pixel(x, y);
      const bool in = x >= 8 && x < 12 && y >= 8 && y < 12;
      const std::array<uint8_t, 3> want = in ? sprite_texel(x - 8, y - 8) : std::array<uint8_t, 3>{0, 0, 0};
      ASSERT_EQ((std::array<uint8_t, 3>{p[0], p[1], p[2]}), want) << x << "," << y;
    }
  EXPECT_EQ(st.texture.samples[size_t(TexFilter::Nearest)], 16u);
  // The square's two triangles meet on the diagonal x = y: the quads (8..9, 8..9) and
  // (10..11, 10..11) hold pixels of both (each has (x + 1, y) above the diagonal and
  // (x, y + 1) below it), so each triangle shades all 4 of them, 4 helpers a quad; the other
  // two quads lie inside one triangle: 8 helper pixels.
  EXPECT_EQ(st.texture.helper_pixels, 8u);
}

// Without point_sprite the square keeps the vertex's texcoord (0.6, 0.1): one texel, (2, 0).
TEST(TextureSprite, WithoutSpriteOneTexel) {
  RenderStats st;
  const Framebuffer fb = render_sprite(false, st);
  for (int y = 8; y < 12; ++y)
    for (int x = 8; x < 12; ++x) {
      const uint8_t* p = fb.pixel(x, y);
      ASSERT_EQ((std::array<uint8_t, 3>{p[0], p[1], p[2]}), sprite_texel(2, 0)) << x << "," << y;
    }
}

}  // namespace
}  // namespace rastsim
