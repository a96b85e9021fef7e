// SPDX-License-Identifier: Apache-2.0
// The depth writes of d full-screen layers drawn in a uniformly random order, depth
// function less, depth writes on: a layer writes a pixel exactly when it is nearer than
// every layer drawn before it (a left-to-right minimum, a "record" of the order), so a
// pixel's writes are the records of a random permutation of d, whose mean is the harmonic
// number H_d = 1 + 1/2 + ... + 1/d and whose variance is sum_k (1/k - 1/k^2) (record k is
// an independent Bernoulli(1/k)). Both are exact: the test checks every order's writes
// against its records counted here, and the mean over many seeded orders against H_d
// within 4 standard errors of the exact variance.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "config/config.h"
#include "config/raster_state_config.h"
#include "ref/pipeline.h"

namespace rastsim {
namespace {

constexpr int kSize = 16;  // framebuffer and viewport edge, px

// One triangle covering every pixel centre of the kSize x kSize viewport, at depth z.
CmdPrimitives full_screen_layer(double z) {
  CmdPrimitives p;
  const double far = 3.0 * kSize;  // past the screen: the triangle covers it whole
  for (auto [x, y] : {std::pair{-1.0, -1.0}, std::pair{far, -1.0}, std::pair{-1.0, far}}) {
    SceneVertex v;
    v.x = Q64::from_double(x);
    v.y = Q64::from_double(y);
    v.z = z;
    v.r = 255;
    p.vertices.push_back(v);
  }
  return p;
}

// The left-to-right minima of `depths` (strictly nearer than all before).
uint64_t records(const std::vector<int>& depths) {
  uint64_t n = 0;
  int nearest = INT32_MAX;
  for (int z : depths)
    if (z < nearest) {
      nearest = z;
      ++n;
    }
  return n;
}

TEST(DepthHarmonic, RandomOrderLayersWriteHdPerPixel) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = kSize;
  st.depth_func = DepthFunc::Less;
  st.depth_write = true;
  constexpr int kOrders = 1000;  // per d
  constexpr uint64_t kPixels = uint64_t(kSize) * kSize;
  std::mt19937_64 rng(29);
  for (int d : {2, 4, 8, 16}) {
    double h = 0, var = 0;
    for (int k = 1; k <= d; ++k) {
      h += 1.0 / k;
      var += 1.0 / k - 1.0 / (double(k) * k);
    }
    std::vector<int> order(size_t(d), 0);
    double sum = 0;
    for (int n = 0; n < kOrders; ++n) {
      std::iota(order.begin(), order.end(), 1);
      for (size_t i = order.size() - 1; i > 0; --i)  // Fisher-Yates, uniform over the d! orders
        std::swap(order[i], order[std::uniform_int_distribution<size_t>(0, i)(rng)]);
      Scene scene;
      scene.commands.push_back({CmdViewport{kSize, kSize}, {"harmonic", 1}});
      for (int layer : order) scene.commands.push_back({full_screen_layer(layer / (d + 1.0)), {"harmonic", 2}});
      RenderStats stats;
      render_scene(scene, st, stats);
      ASSERT_EQ(stats.depth_writes, kPixels * records(order)) << "d = " << d << ", order " << n;
      sum += double(stats.depth_writes) / double(kPixels);
    }
    const double mean = sum / kOrders, bound = 4 * std::sqrt(var / kOrders);
    EXPECT_NEAR(mean, h, bound) << "d = " << d << ": H_d = " << h << ", 4 standard errors = " << bound;
  }
}

// No depth write, no depth writes counted, whatever passes.
TEST(DepthHarmonic, NoDepthWritesWithDepthWriteOff) {
  RasterState st = raster_state_from_config(Config{});
  st.fb_width = st.fb_height = kSize;
  st.depth_func = DepthFunc::Less;
  st.depth_write = false;
  Scene scene;
  scene.commands.push_back({CmdViewport{kSize, kSize}, {"harmonic", 1}});
  for (double z : {0.5, 0.25}) scene.commands.push_back({full_screen_layer(z), {"harmonic", 2}});
  RenderStats stats;
  render_scene(scene, st, stats);
  EXPECT_EQ(stats.samples_passed, 2 * uint64_t(kSize) * kSize);
  EXPECT_EQ(stats.depth_writes, 0u);
}

}  // namespace
}  // namespace rastsim
