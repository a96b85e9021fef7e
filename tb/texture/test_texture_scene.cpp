// SPDX-License-Identifier: Apache-2.0
// Textures in scenes: image files (PNG, TGA) decoded top row first, the trace commands and
// their errors (file:line), the OBJ map_Kd, a textured quad rendered texel for texel,
// helper pixels counted by hand, untextured scenes unchanged, and the refusal of the
// levels without a texture stage (ctest -L texture).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "config/config.h"
#include "config/obj_placement.h"
#include "config/raster_state_config.h"
#include "image/image_io.h"
#include "ref/pipeline.h"
#include "scene/scene_io.h"
#include "scene/texture_file.h"

namespace rastsim {
namespace texture_test {
std::string jpeg_bytes(int w, int h, const std::vector<unsigned char>& rgb);  // stb_image_write_impl.cpp
}  // namespace texture_test
namespace {

namespace fs = std::filesystem;

const std::string kData = RASTSIM_TEST_DATA;

// A scratch directory of this test process, removed at the end of each test.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("rastsim_texture_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  std::string put(const std::string& name, const std::string& bytes) const {
    std::ofstream((dir / name).string(), std::ios::binary) << bytes;
    return (dir / name).string();
  }
};

// An uncompressed 32-bit TGA, top-left origin, of w x h RGBA texels (row 0 first).
std::string tga(int w, int h, const std::vector<uint8_t>& rgba) {
  std::string b = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, char(w & 255), char(w >> 8), char(h & 255), char(h >> 8),
                   32, 0x28};
  for (size_t k = 0; k + 3 < rgba.size(); k += 4)
    b += {char(rgba[k + 2]), char(rgba[k + 1]), char(rgba[k]), char(rgba[k + 3])};
  return b;
}

// A 4 x 4 texture whose texel (i, j) is (40 i, 40 j, 7, 255).
std::vector<uint8_t> ramp4() {
  std::vector<uint8_t> v;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) v.insert(v.end(), {uint8_t(40 * i), uint8_t(40 * j), 7, 255});
  return v;
}

::testing::AssertionResult fails_with(const std::function<void()>& fn, const std::string& where,
                                      const std::string& phrase) {
  try {
    fn();
  } catch (const SceneError& e) {
    const std::string m = e.what();
    if (m.rfind(where + " ", 0) == 0 && m.find(phrase) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "message: " << m;
  }
  return ::testing::AssertionFailure() << "no SceneError";
}

RasterState default_raster() { return raster_state_from_config(Config{}); }

TEST(TextureFiles, PngAndTgaDecodeTopRowFirst) {
  Scratch s;
  const std::string t = s.put("a.tga", tga(4, 4, ramp4()));
  Framebuffer fb(4, 4);
  const auto ramp = ramp4();
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) std::copy_n(&ramp[size_t(j * 4 + i) * 4], 4, fb.pixel(i, j));
  write_image(fb, (s.dir / "a.png").string());
  const auto a = load_texture_file(t, "x.trace", 1), b = load_texture_file((s.dir / "a.png").string(), "x.trace", 1);
  EXPECT_EQ(a->width, 4);
  EXPECT_EQ(a->rgba, ramp);
  EXPECT_EQ(b->rgba, ramp);
}

// JPEG is lossy: a uniform image at quality 100 decodes within 2 of its colour.
TEST(TextureFiles, JpegDecodes) {
  Scratch s;
  std::vector<unsigned char> rgb;
  for (int k = 0; k < 16 * 8; ++k) rgb.insert(rgb.end(), {200, 120, 40});
  const std::string path = s.put("a.jpg", texture_test::jpeg_bytes(16, 8, rgb));
  const auto t = load_texture_file(path, "x.trace", 1);
  ASSERT_EQ(t->width, 16);
  ASSERT_EQ(t->height, 8);
  for (size_t k = 0; k < t->rgba.size(); k += 4) {
    EXPECT_NEAR(t->rgba[k], 200, 2);
    EXPECT_NEAR(t->rgba[k + 1], 120, 2);
    EXPECT_NEAR(t->rgba[k + 2], 40, 2);
    EXPECT_EQ(t->rgba[k + 3], 255);
  }
}

TEST(TextureFiles, BadFilesNameTheReferringLine) {
  Scratch s;
  s.put("junk.png", "not an image at all");
  std::string cut = tga(4, 4, ramp4());
  cut.resize(cut.size() - 5);
  s.put("cut.tga", cut);
  std::string png;
  {
    Framebuffer fb(8, 8);
    write_image(fb, (s.dir / "whole.png").string());
    std::ifstream in(s.dir / "whole.png", std::ios::binary);
    png.assign(std::istreambuf_iterator<char>(in), {});
  }
  s.put("cut.png", png.substr(0, png.size() / 2));
  s.put("wide.tga", tga(20000, 1, std::vector<uint8_t>(20000 * 4, 9)));  // a side above 16384
  const std::string trace = (s.dir / "t.trace").string();
  for (const auto& [file, phrase] : std::vector<std::pair<std::string, std::string>>{
           {"gone.png", "no such file"}, {"junk.png", "not a readable PNG, TGA or JPEG image"},
           {"cut.tga", "truncated TGA"}, {"cut.png", "not a readable PNG, TGA or JPEG image"},
           {"wide.tga", "not a readable PNG, TGA or JPEG image (too large)"}}) {
    SCOPED_TRACE(file);
    EXPECT_TRUE(fails_with([&] { parse_trace("clear 0 0 0\ntexture 3 " + file + "\ntri 0 0 1 0 0 1\n", trace); },
                           trace + ":2:", "texture '" + (s.dir / file).string() + "': " + phrase));
  }
  // An MTL's map_Kd: the MTL's line.
  s.put("m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd junk.png\n");
  EXPECT_TRUE(fails_with([&] { parse_obj("mtllib m.mtl\n", "x.obj", obj_placement_from_config(Config{}), s.dir.string()); },
                         (s.dir / "m.mtl").string() + ":3:", "not a readable PNG"));
}

TEST(TextureTrace, CommandsAndTheirErrors) {
  Scratch s;
  s.put("r.tga", tga(4, 4, ramp4()));
  const std::string trace = (s.dir / "t.trace").string();
  const Scene sc = parse_trace("texture 2 r.tga\nbindtexture 2\ntexfilter trilinear\ntexwrap clamp mirror\n"
                               "texenv decal\nmipmap on\ntexlod_bias -1.5\ntri 0 0 1 0 0 1\nbindtexture none\n"
                               "tri 0 0 1 0 0 1\n",
                               trace);
  const auto& p = std::get<CmdPrimitives>(sc.commands[0].body);
  ASSERT_TRUE(p.texture.enabled());
  EXPECT_EQ(p.texture.image->width, 4);
  EXPECT_EQ(p.texture.filter, TexFilter::Trilinear);
  EXPECT_EQ(p.texture.wrap_s, TexWrap::Clamp);
  EXPECT_EQ(p.texture.wrap_t, TexWrap::Mirror);
  EXPECT_EQ(p.texture.env, TexEnv::Decal);
  EXPECT_TRUE(p.texture.mipmap);
  EXPECT_EQ(p.texture.lod_bias, -384);
  EXPECT_FALSE(std::get<CmdPrimitives>(sc.commands[1].body).texture.enabled());
  const auto bad = [&](const std::string& line, const std::string& phrase) {
    EXPECT_TRUE(fails_with([&] { parse_trace("texture 2 r.tga\n" + line + "\ntri 0 0 1 0 0 1\n", trace); },
                           trace + ":2:", phrase))
        << line;
  };
  bad("bindtexture 5", "texture ID 5 is not loaded");
  bad("texfilter linear", "texfilter 'linear' is not 'nearest', 'bilinear' or 'trilinear'");
  bad("texwrap repeat clamp mirror", "'texwrap' takes 1 argument");
  bad("texenv add", "texenv 'add' is not 'replace', 'modulate' or 'decal'");
  bad("mipmap yes", "mipmap 'yes' is not 'off' or 'on'");
  bad("texlod_bias 17", "texlod_bias '17' is outside [-16, 16]");
  bad("texture 70000 r.tga", "texture ID 70000 is outside 0..65535");
  EXPECT_TRUE(fails_with([&] { parse_trace("strip\nv 0 0\ntexfilter nearest\n", trace); }, trace + ":3:",
                         "inside the 'strip'"));
}

// An 8 x 8-pixel quad mapped to the 4 x 4 ramp, nearest, replace: pixel (x, y)'s centre
// ((x + 1/2) / 8, (y + 1/2) / 8) lies in texel (floor((x + 1/2) / 2), ...) = (x >> 1, y >> 1).
TEST(TextureRender, QuadIsTexelForTexel) {
  Scratch s;
  s.put("r.tga", tga(4, 4, ramp4()));
  const std::string text =
      "texture 1 r.tga\nbindtexture 1\ntexfilter nearest\ntexenv replace\nstrip\ntexcoord 0 0\nv 0 0\n"
      "texcoord 1 0\nv 8 0\ntexcoord 0 1\nv 0 8\ntexcoord 1 1\nv 8 8\nend\n";
  const Scene sc = parse_trace(text, (s.dir / "t.trace").string());
  RenderStats st;
  const Framebuffer fb = render_scene(sc, default_raster(), st);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint8_t* p = fb.pixel(x, y);
      ASSERT_EQ(p[0], 40 * (x >> 1)) << x << "," << y;
      ASSERT_EQ(p[1], 40 * (y >> 1)) << x << "," << y;
      ASSERT_EQ(p[2], 7);
    }
  EXPECT_EQ(fb.pixel(8, 0)[0], 0);  // outside the quad: the clear colour
  EXPECT_EQ(st.texture.samples[size_t(TexFilter::Nearest)], 64u);
  EXPECT_EQ(st.texture.texel_fetches, 64u);  // one a nearest sample
  // Helper pixels are per triangle: the 4 quads the diagonal x + y = 7 crosses hold pixel
  // sums 6, 7, 7, 8; the two on the edge go to one triangle (3 of the quad's pixels, 1
  // helper), the other triangle has 1 (3 helpers): 4 x 4 = 16.
  EXPECT_EQ(st.texture.helper_pixels, 16u);
}

// The same 8 x 8-pixel quad over a 32 x 32 texture of uniform 4 x 4 blocks (block (a, b)
// is (30 a, 30 b, 100)), mipmapped, nearest: ds/dx = 1/8, 4 texels a pixel, lambda = 2
// exactly: level 2 (8 x 8), whose texel (x, y) is block (x, y) (boxes of equal texels).
// With texlod_bias 1, level 3 (4 x 4): texel (x >> 1, y >> 1), the box of blocks 2k and
// 2k + 1 twice: (2 (60k) + 2 (60k + 30) + 2) >> 2 = 60k + 15.
TEST(TextureRender, QuadLevelOfDetailPicksTheMipLevel) {
  Scratch s;
  std::vector<uint8_t> blocks;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) blocks.insert(blocks.end(), {uint8_t(30 * (i >> 2)), uint8_t(30 * (j >> 2)), 100, 255});
  s.put("b.tga", tga(32, 32, blocks));
  const std::string quad = "strip\ntexcoord 0 0\nv 0 0\ntexcoord 1 0\nv 8 0\ntexcoord 0 1\nv 0 8\ntexcoord 1 1\nv 8 8\nend\n";
  for (int bias = 0; bias <= 1; ++bias) {
    const Scene sc = parse_trace("texture 1 b.tga\nbindtexture 1\ntexfilter nearest\ntexenv replace\nmipmap on\n"
                                 "texlod_bias " + std::to_string(bias) + "\n" + quad,
                                 (s.dir / "t.trace").string());
    RenderStats st;
    const Framebuffer fb = render_scene(sc, default_raster(), st);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const int want_r = bias ? 60 * (x >> 1) + 15 : 30 * x, want_g = bias ? 60 * (y >> 1) + 15 : 30 * y;
        ASSERT_EQ(fb.pixel(x, y)[0], want_r) << x << "," << y << " bias " << bias;
        ASSERT_EQ(fb.pixel(x, y)[1], want_g) << x << "," << y << " bias " << bias;
        ASSERT_EQ(fb.pixel(x, y)[2], 100);
      }
  }
}

// Triangle (0, 0), (4.2, 0), (0, 4.2): centres with x + y + 1 < 4.2 are covered, 10 pixels
// in 3 quads (4 + 3 + 3; the quad at (2..3, 2..3) has none): 12 - 10 = 2 helper pixels.
TEST(TextureRender, HelperPixelsHandCounted) {
  Scratch s;
  s.put("r.tga", tga(4, 4, ramp4()));
  const Scene sc = parse_trace("texture 1 r.tga\nbindtexture 1\ntri 0 0 4.2 0 0 4.2\n", (s.dir / "t.trace").string());
  RenderStats st;
  render_scene(sc, default_raster(), st);
  EXPECT_EQ(st.fragments_shaded, 10u);
  EXPECT_EQ(st.texture.helper_pixels, 2u);
  EXPECT_EQ(st.texture.samples[size_t(TexFilter::Bilinear)], 10u);
}

// A loaded but unbound texture, or `bindtexture none`, changes nothing.
TEST(TextureRender, UnboundTextureChangesNothing) {
  Scratch s;
  s.put("r.tga", tga(4, 4, ramp4()));
  const std::string draw = "color 200 100 50\ntri 0 0 30 0 0 20\ntri 5 5 40 9 7 33\n";
  RenderStats plain, unbound;
  render_scene(parse_trace(draw, "t.trace"), default_raster(), plain);
  render_scene(parse_trace("texture 1 r.tga\nbindtexture 1\nbindtexture none\n" + draw, (s.dir / "t.trace").string()),
               default_raster(), unbound);
  EXPECT_EQ(plain.framebuffer_crc32, unbound.framebuffer_crc32);
  EXPECT_EQ(unbound.texture.total_samples(), 0u);
}

// The notes-style textured box: every face textured, modulating the shaded colour.
TEST(TextureRender, TexturedBoxObjRenders) {
  const Scene sc = load_obj(kData + "/boxT.obj", obj_placement_from_config(Config{}));
  size_t textured = 0;
  for (const Command& c : sc.commands)
    if (const auto* p = std::get_if<CmdPrimitives>(&c.body); p && p->texture.enabled()) ++textured;
  EXPECT_GT(textured, 0u);
  RenderStats st;
  RasterState rs = default_raster();
  rs.cull = CullMode::Back;
  const Framebuffer fb = render_scene(sc, rs, st);
  EXPECT_EQ(st.texture.samples[size_t(TexFilter::Bilinear)], st.fragments_shaded);
  EXPECT_EQ(st.texture.texel_fetches, 4 * st.fragments_shaded);  // bilinear, mipmap off: 4 texels a sample
  EXPECT_EQ(st.texture.cache_hits + st.texture.cache_misses, st.texture.texel_fetches);
  EXPECT_GT(st.texture.helper_pixels, 0u);
  // The checker's two colours both reach the image (the untextured box is grey only).
  bool warm = false, cool = false;
  for (int y = 0; y < fb.height; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const uint8_t* p = fb.pixel(x, y);
      warm = warm || (p[0] > p[2] + 40);
      cool = cool || (p[2] > p[0] + 40);
    }
  EXPECT_TRUE(warm);
  EXPECT_TRUE(cool);
}

// scene.obj_texfilter and scene.obj_mipmap set every textured face's filter and mipmap
// (MTL has neither): nearest reads one texel a fragment; trilinear mipmapped is counted
// as trilinear samples (the box magnifies its texture: level 0, one level read).
TEST(TextureRender, ObjFilterAndMipmapKeys) {
  Config cfg;
  cfg.set_from_string("scene.obj_texfilter", "nearest", "test");
  RasterState rs = default_raster();
  rs.cull = CullMode::Back;
  RenderStats nearest;
  render_scene(load_obj(kData + "/boxT.obj", obj_placement_from_config(cfg)), rs, nearest);
  EXPECT_GT(nearest.fragments_shaded, 0u);
  EXPECT_EQ(nearest.texture.samples[size_t(TexFilter::Nearest)], nearest.fragments_shaded);
  EXPECT_EQ(nearest.texture.texel_fetches, nearest.fragments_shaded);
  cfg.set_from_string("scene.obj_texfilter", "trilinear", "test");
  cfg.set_from_string("scene.obj_mipmap", "true", "test");
  const Scene sc = load_obj(kData + "/boxT.obj", obj_placement_from_config(cfg));
  size_t textured = 0;
  for (const Command& c : sc.commands)
    if (const auto* p = std::get_if<CmdPrimitives>(&c.body); p && p->texture.enabled()) {
      ++textured;
      EXPECT_EQ(p->texture.filter, TexFilter::Trilinear);
      EXPECT_TRUE(p->texture.mipmap);
    }
  EXPECT_GT(textured, 0u);
  RenderStats tri;
  render_scene(sc, rs, tri);
  EXPECT_EQ(tri.texture.samples[size_t(TexFilter::Trilinear)], tri.fragments_shaded);
  EXPECT_EQ(tri.fragments_shaded, nearest.fragments_shaded);
}

}  // namespace
}  // namespace rastsim
