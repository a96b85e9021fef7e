// SPDX-License-Identifier: Apache-2.0
// The timed model with raster.samples > 1 (docs/antialiasing.md, docs/microarchitecture.md
// "Multisampling"):
//
// - for 2, 4, 8 and 16 samples, msaa and ssaa, on seeded random scenes and with every
//   exact traversal, the resolved image, depth, fragment stream (with masks) and every
//   counter equal render_scene's;
// - one hand-worked triangle whose masks are counted here on paper checks the fine raster
//   (A S tests), ROP (the full-mask compression rule) and resolve cycle equations, and
//   the traffic stats;
// - 2D commands with raster.samples > 1 are the reference model's error.
#include <gtest/gtest.h>

#include "sim_harness.h"
#include "scene/scene_io.h"

namespace rastsim::sctest {
namespace {

TEST(ScMultisample, RandomScenesMatchReference) {
  for (int samples : {2, 4, 8, 16}) {
    for (const char* mode : {"msaa", "ssaa"}) {
      for (uint64_t seed : {1u, 2u}) {
        SCOPED_TRACE(std::to_string(samples) + " " + mode + " seed " + std::to_string(seed));
        const Scene scene = random_scene(seed * 31 + uint64_t(samples), 96, 72, 40);
        const Config cfg = make_config({"raster.samples=" + std::to_string(samples), std::string("raster.aa_mode=") + mode,
                                        "display.width=96", "display.height=72",
                                        seed == 1 ? "raster.depth_func=less" : "raster.cull=back"});
        sc::SimOptions o;
        if (seed == 2) {  // stalls change no image
          o.stall_seed = 9;
          o.stall_probability = 0.2;
        }
        const nlohmann::json r = run_isolated([&] { return compare_with_reference(scene, cfg, o); });
        expect_matches_reference(r);
        if (r.contains("error")) continue;
        const auto& s = r["stats"];
        EXPECT_EQ(s["samples"], samples);
        EXPECT_EQ(s["aa_mode"], mode);
        EXPECT_EQ(s["sample_tests"].get<uint64_t>(), s["pixel_tests"].get<uint64_t>() * uint64_t(samples));
        EXPECT_GT(s["pixels_partially_covered"].get<uint64_t>(), 0u);
        // The resolve pass: W H S 4 + W H 4 bytes at 64 a cycle, in the ROP's busy cycles.
        const uint64_t resolve = (96u * 72u * uint64_t(samples) * 4 + 96u * 72u * 4 + 63) / 64;
        EXPECT_EQ(s["resolve_cycles"].get<uint64_t>(), resolve);
        EXPECT_GE(s["stages"]["rop"]["busy"].get<uint64_t>(), resolve);
        // msaa: one fragment a pixel; ssaa: one a covered sample, one access each.
        if (std::string(mode) == "msaa") {
          EXPECT_EQ(s["fragments_shaded"], s["fragments"]);
          EXPECT_LT(s["rop_accesses"].get<uint64_t>(), s["samples_covered"].get<uint64_t>());
        } else {
          EXPECT_EQ(s["fragments_shaded"], s["samples_covered"]);
          EXPECT_EQ(s["rop_accesses"], s["samples_covered"]);
        }
      }
    }
  }
}

TEST(ScMultisample, EveryExactTraversalMatchesReference) {
  for (const char* traversal : {"tiled", "bbox", "hierarchical"}) {
    for (const char* mode : {"msaa", "ssaa"}) {
      SCOPED_TRACE(std::string(traversal) + " " + mode);
      const Config cfg = make_config({std::string("raster.traversal=") + traversal, std::string("raster.aa_mode=") + mode,
                                      "raster.samples=4", "raster.tile_size=8", "raster.hier_levels=32/8/2",
                                      "raster.depth_func=less", "fifo.tile_depth=1", "fifo.pixel_depth=1"});
      const Scene scene = random_scene(77, 128, 96, 50);
      expect_matches_reference(run_isolated([&] { return compare_with_reference(scene, cfg); }));
    }
  }
}

// One right triangle (0,0) (8,0) (0,8) in an 8x8 viewport and framebuffer, one 8x8 tile,
// at 4 samples, offsets (-2,-6) (6,-2) (-6,2) (2,6) / 16 from the centre. Pixel (x, y)
// has centre coordinate sum x + y + 1; its samples add -8, 4, -4, 8 sixteenths, and a
// sample is inside when its sum is < 8 (no sample lies on the hypotenuse; the other two
// edges are 1/8 pixel away from the nearest sample). So:
// - x + y <= 6: 28 pixels, all 4 samples (full mask);
// - x + y = 7: 8 pixels, samples 0 and 2 (sums 7.5 and 7.75): partial, 2 samples;
// - x + y >= 8: no sample.
TEST(ScMultisample, HandWorkedTimingOfOneTile) {
  const Scene scene = parse_trace("viewport 8 8\ntri 0 0 0.5 255 0 0 8 0 0.5 0 255 0 0 8 0.5 0 0 255\n", "hand");
  const std::vector<std::string> base{"display.width=8",          "display.height=8",
                                      "raster.tile_size=8",       "raster.samples=4",
                                      "fine.samples_per_cycle=16", "rop.pixels_per_cycle=4",
                                      "interp.fragments_per_cycle=4", "rop.resolve_bytes_per_cycle=64"};
  for (const char* mode : {"msaa", "ssaa"}) {
    SCOPED_TRACE(mode);
    auto sets = base;
    sets.push_back(std::string("raster.aa_mode=") + mode);
    const nlohmann::json r = run_isolated([&, cfg = make_config(sets)] { return compare_with_reference(scene, cfg); });
    expect_matches_reference(r);
    if (r.contains("error")) continue;
    const auto& s = r["stats"];
    const bool ssaa = std::string(mode) == "ssaa";
    // Coverage, as worked out above.
    EXPECT_EQ(s["tiles_partial"], 1);
    EXPECT_EQ(s["tiles_accepted"], 0);
    EXPECT_EQ(s["pixel_tests"], 64);
    EXPECT_EQ(s["sample_tests"], 256);
    EXPECT_EQ(s["fragments"], 36);
    EXPECT_EQ(s["samples_covered"], 28 * 4 + 8 * 2);
    EXPECT_EQ(s["pixels_partially_covered"], 8);
    // Interpolation: msaa 36 fragments; ssaa one a covered sample, 128.
    const uint64_t shaded = ssaa ? 128 : 36;
    EXPECT_EQ(s["fragments_shaded"], shaded);
    // ROP accesses: msaa 28 full pixels once each + 8 partial x 2 samples = 44;
    // ssaa one a fragment, 128.
    const uint64_t accesses = ssaa ? 128 : 28 + 8 * 2;
    EXPECT_EQ(s["rop_accesses"], accesses);
    // Resolve: 8 x 8 x 4 x 4 read + 8 x 8 x 4 written = 1280 bytes at 64 a cycle.
    EXPECT_EQ(s["resolve_cycles"], 20);
    EXPECT_EQ(s["resolve_bytes"], 1280);
    // Bytes: accesses x (4 colour + 3 depth bytes) + the resolve (no clear here).
    EXPECT_EQ(s["framebuffer_bytes"], accesses * 7 + 1280);
    // Busy cycles. Every stage passes the viewport command and the end-of-frame marker in
    // 1 cycle each (fine, interpolation), the ROP the viewport in 1.
    // Fine: 64 pixels x 4 samples at 16 a cycle = 16.
    EXPECT_EQ(s["stages"]["fine_raster"]["busy"], 2 + 16);
    // Interpolation: the shaded fragments at 4 a cycle.
    EXPECT_EQ(s["stages"]["interpolate"]["busy"], 2 + (shaded + 3) / 4);
    // ROP: the viewport, accesses at 4 a cycle (msaa 11, ssaa 32), the resolve's 20.
    EXPECT_EQ(s["stages"]["rop"]["busy"], 1 + accesses / 4 + 20);
  }
}

TEST(ScMultisample, OneSampleHasNoResolveAndOneAccessAFragment) {
  const Scene scene = random_scene(5, 96, 72, 30);
  const nlohmann::json r = run_isolated([&, cfg = make_config({"display.width=96", "display.height=72"})] {
    return compare_with_reference(scene, cfg);
  });
  expect_matches_reference(r);
  if (r.contains("error")) return;
  const auto& s = r["stats"];
  EXPECT_EQ(s["resolve_cycles"], 0);
  EXPECT_EQ(s["resolve_bytes"], 0);
  EXPECT_EQ(s["rop_accesses"], s["fragments"]);
  EXPECT_EQ(s["fragments_shaded"], s["fragments"]);
  EXPECT_FALSE(s.contains("aa_mode"));
  // A clear moves W x H x 4 colour or W x H x 3 depth bytes; count them from the scene.
  uint64_t clears = 0;
  for (const Command& c : scene.commands) {
    if (std::holds_alternative<CmdClear>(c.body)) clears += 96 * 72 * 4;
    if (std::holds_alternative<CmdClearDepth>(c.body)) clears += 96 * 72 * 3;
  }
  EXPECT_EQ(s["framebuffer_bytes"].get<uint64_t>(), s["fragments"].get<uint64_t>() * 7 + clears);
}

TEST(ScMultisample, Draw2dWithSamplesIsTheReferenceError) {
  const Scene scene = parse_trace("viewport 32 32\nrect 2 2 10 10\n", "d2");
  const nlohmann::json r =
      run_isolated([&, cfg = make_config({"raster.samples=4"})] { return simulate_stats(scene, cfg); });
  ASSERT_TRUE(r.contains("error"));
  EXPECT_NE(r["error"].get<std::string>().find("raster.samples = 4"), std::string::npos) << r["error"];
}

}  // namespace
}  // namespace rastsim::sctest
