// SPDX-License-Identifier: Apache-2.0
// depth.early (docs/depth.md): the depth test before colour and texture work changes no
// image and no ROP count, only the fragments that reach interpolation's colour stage and
// the texture unit. Checked on a hand-worked scene (exact culled counts), on every shipped
// trace and the textured box under several depth states, and on seeded random scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "config/config.h"
#include "config/memory_config.h"
#include "config/obj_placement.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"
#include "scene_test.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

using scene_test::screen_vertex;
SceneVertex vertex(double x, double y, double z, uint8_t r) { return screen_vertex(x, y, z, r); }

// The axis-aligned quad [x0, x1) x [y0, y1) (pixel edges: it covers the pixel centres
// inside, (x1 - x0) (y1 - y0) pixels) at depth z, as two triangles.
CmdPrimitives quad(int x0, int y0, int x1, int y1, double z, uint8_t r) {
  CmdPrimitives p;
  p.vertices = {vertex(x0, y0, z, r), vertex(x1, y0, z, r), vertex(x0, y1, z, r),
                vertex(x1, y0, z, r), vertex(x1, y1, z, r), vertex(x0, y1, z, r)};
  return p;
}

struct Pair {
  RenderStats late, early;
};

// `scene` rendered with depth.early off and on; the images' CRCs and every ROP count equal.
Pair render_both(const Scene& scene, RasterState st, const MemoryParams& memory = {}) {
  Pair r;
  st.depth_early = false;
  render_scene(scene, st, r.late, {}, Framebuffer::kDefaultTileLog2, 1, memory);
  st.depth_early = true;
  render_scene(scene, st, r.early, {}, Framebuffer::kDefaultTileLog2, 1, memory);
  EXPECT_EQ(r.early.framebuffer_crc32, r.late.framebuffer_crc32);
  EXPECT_EQ(r.early.fragments_passed, r.late.fragments_passed);
  EXPECT_EQ(r.early.samples_passed, r.late.samples_passed);
  EXPECT_EQ(r.early.depth_writes, r.late.depth_writes);
  EXPECT_EQ(r.early.fragments_shaded + r.early.fragments_culled_early, r.late.fragments_shaded);
  EXPECT_EQ(r.late.fragments_culled_early, 0u);
  return r;
}

// Two 10 x 10 quads on a 16 x 16 screen overlapping in 5 x 5 pixels, depth less: front
// (z 0.2, pixels 0..9) then back (z 0.6, pixels 5..14): the back quad's 25 overlapped
// pixels fail the depth test, so early Z culls exactly those 25, each saving its 3 colour
// interpolations; drawn back to front nothing fails and nothing is culled.
TEST(DepthEarly, TwoQuadsFrontToBackHandCounted) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = 16;
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  const CmdPrimitives front = quad(0, 0, 10, 10, 0.2, 255), back = quad(5, 5, 15, 15, 0.6, 128);
  for (bool front_first : {true, false}) {
    SCOPED_TRACE(front_first ? "front to back" : "back to front");
    Scene scene;
    scene.commands.push_back({CmdViewport{16, 16}, {"hand", 1}});
    scene.commands.push_back({front_first ? front : back, {"hand", 2}});
    scene.commands.push_back({front_first ? back : front, {"hand", 3}});
    const Pair r = render_both(scene, st);
    EXPECT_EQ(r.late.fragments_shaded, 200u);
    EXPECT_EQ(r.early.fragments_culled_early, front_first ? 25u : 0u);
    EXPECT_EQ(r.early.interpolations_saved, front_first ? 75u : 0u);
    EXPECT_EQ(r.early.texture_samples_saved, 0u);
    EXPECT_EQ(r.early.depth_writes, front_first ? 175u : 200u);
  }
  // never: every fragment fails, and is culled early; always: none is.
  Scene scene;
  scene.commands.push_back({CmdViewport{16, 16}, {"hand", 1}});
  scene.commands.push_back({front, {"hand", 2}});
  st.depth_func = DepthFunc::Never;
  EXPECT_EQ(render_both(scene, st).early.fragments_culled_early, 100u);
  st.depth_func = DepthFunc::Always;
  EXPECT_EQ(render_both(scene, st).early.fragments_culled_early, 0u);
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> paths;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(RASTSIM_SOURCE_DIR) / "traces"))
    if (e.is_regular_file() && e.path().extension() == ".trace") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  paths.push_back((fs::path(RASTSIM_SOURCE_DIR) / "tb" / "data" / "boxT.obj").string());  // textured, closed
  return paths;
}

// Every shipped trace and the textured box, under depth functions that cull and do not,
// one and four samples (msaa, ssaa), depth writes on and off, and the memory system on.
TEST(DepthEarly, ShippedScenesSameImageAndCounts) {
  Config mem_cfg;
  mem_cfg.apply_override("memory.model=dram");
  const MemoryParams memory = memory_params_from_config(mem_cfg);
  for (const std::string& path : shipped_scenes()) {
    SCOPED_TRACE(path);
    const Scene scene = load_scene(path, obj_placement_from_config(Config{}));
    const bool has_2d = std::any_of(scene.commands.begin(), scene.commands.end(),
                                    [](const Command& c) { return std::holds_alternative<CmdDraw2d>(c.body); });
    for (DepthFunc func : {DepthFunc::Less, DepthFunc::GEqual, DepthFunc::Always})
      for (int variant = 0; variant < 4; ++variant) {
        RasterState st = raster_state_from_config(Config{});
        st.depth_func = func;
        st.depth_write = variant != 1;
        if (variant == 2 && !has_2d) st.samples = 4;
        if (variant == 3 && !has_2d) {
          st.samples = 4;
          st.aa_mode = AaMode::Ssaa;
        }
        SCOPED_TRACE("depth_func " + std::to_string(int(func)) + ", variant " + std::to_string(variant));
        const Pair r = render_both(scene, st, variant == 0 ? memory : MemoryParams{});
        // The memory system sees the same accesses: the culled fragments' depth reads early.
        EXPECT_EQ(r.early.memory.rop_depth.accesses, r.late.memory.rop_depth.accesses);
        EXPECT_EQ(r.early.memory.rop_depth.bytes_read, r.late.memory.rop_depth.bytes_read);
        EXPECT_EQ(r.early.memory.rop_color.bytes_written, r.late.memory.rop_color.bytes_written);
        // Texture samples not taken are exactly those of the culled textured fragments.
        EXPECT_EQ(r.early.texture.total_samples() + r.early.texture_samples_saved, r.late.texture.total_samples());
        if (func == DepthFunc::Always) {
          EXPECT_EQ(r.early.fragments_culled_early, 0u);
        }
      }
  }
}

// Seeded random scenes: overlapping triangles at random depths and colours, every depth
// function, one and four samples.
TEST(DepthEarly, RandomScenesSameImage) {
  std::mt19937 rng(2929);
  std::uniform_real_distribution<double> xy(-4, 36), z(0, 1);
  std::uniform_int_distribution<int> c(0, 255);
  uint64_t culled = 0;
  for (int n = 0; n < 40; ++n) {
    Scene scene;
    scene.commands.push_back({CmdViewport{32, 32}, {"random", 1}});
    CmdPrimitives p;
    for (int v = 0; v < 3 * 12; ++v) p.vertices.push_back(vertex(xy(rng), xy(rng), z(rng), uint8_t(c(rng))));
    scene.commands.push_back({p, {"random", 2}});
    RasterState st = raster_state_from_config(Config{});
    st.fb_width = st.fb_height = 32;
    st.depth_func = DepthFunc(n % 8);
    st.depth_write = n % 5 != 0;
    st.samples = n % 3 == 0 ? 4 : 1;
    st.aa_mode = n % 6 == 3 ? AaMode::Ssaa : AaMode::Msaa;
    SCOPED_TRACE("scene " + std::to_string(n));
    culled += render_both(scene, st).early.fragments_culled_early;
  }
  EXPECT_GT(culled, 0u);  // the scenes do exercise the early cull
}

}  // namespace
}  // namespace rastsim
