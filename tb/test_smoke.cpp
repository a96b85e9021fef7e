// SPDX-License-Identifier: Apache-2.0
// Smoke test: the default config builds a raster state and an empty scene renders.
#include <gtest/gtest.h>

#include "ref/pipeline.h"
#include "config/raster_state_config.h"

namespace rastsim {

TEST(Smoke, EmptySceneRendersClearColour) {
  const RasterState st = raster_state_from_config(Config{});
  Scene scene;
  scene.commands.push_back({CmdClear{10, 20, 30}, {"mem", 1}});
  RenderStats stats;
  const Framebuffer fb = render_scene(scene, st, stats);
  ASSERT_EQ(fb.width, 128);
  EXPECT_EQ(fb.pixel(5, 7)[0], 10);
  EXPECT_EQ(fb.pixel(127, 127)[2], 30);
  EXPECT_EQ(stats.traversal.fragments, 0u);
}

}  // namespace rastsim
