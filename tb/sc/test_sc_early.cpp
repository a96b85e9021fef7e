// SPDX-License-Identifier: Apache-2.0
// Early Z in the timed model (depth.early, docs/depth-culling.md "Early Z in the timed
// model"): interpolation culls the fragments the reference's early test culls, with the
// same counts (fragments_culled_early, interpolations_saved, texture_samples_saved),
// image, fragment stream and depth buffer, every depth function, sample mode and with
// Hi-Z; with the memory system the memory clients' counts equal the reference's; the
// cycles drop on layers drawn front to back and stay above estimate's lower bound.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "config/arch_params.h"
#include "config/obj_placement.h"
#include "estimate/estimate.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"
#include "scene_test.h"
#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

const std::string kData = std::string(RASTSIM_SOURCE_DIR) + "/tb/data";

// The estimate's lower bound of a scene under cfg (model/estimate), for `cycles` to stay above.
uint64_t estimate_bound(const Scene& scene, const Config& cfg) {
  return estimate_scene(scene, ArchParams::resolve(cfg)).cycles_lower_bound;
}

// Seeded random scenes (clears, scissor, a viewport change) under every depth function,
// depth writes on and off, one sample, 4x msaa and 4x ssaa, Hi-Z off or minmax: the timed
// model matches the reference stat for stat (the early keys included), fragment for
// fragment (the kept ones), and its cycles are >= estimate's bound.
TEST(ScEarlyZ, MatchesReferenceOnRandomScenes) {
  uint64_t culled = 0, seed = 100;
  const char* funcs[] = {"less", "lequal", "greater", "gequal", "equal", "notequal", "never", "always"};
  const std::vector<std::vector<std::string>> modes = {
      {}, {"raster.samples=4"}, {"raster.samples=4", "raster.aa_mode=ssaa"}, {"depth.hiz=minmax", "depth.hiz_bytes=64"}};
  for (const char* func : funcs)
    for (const auto& mode : modes) {
      ++seed;
      std::vector<std::string> sets = {"depth.early=true", std::string("raster.depth_func=") + func,
                                       seed % 2 ? "raster.depth_write=true" : "raster.depth_write=false"};
      sets.insert(sets.end(), mode.begin(), mode.end());
      SCOPED_TRACE(std::string(func) + (mode.empty() ? "" : " " + mode[0]) + " seed " + std::to_string(seed));
      const Config cfg = make_config(sets);
      const Scene scene = random_scene(seed, 64, 48, 50);
      const nlohmann::json r = run_isolated([&] { return compare_with_reference(scene, cfg); });
      expect_matches_reference(r);
      ASSERT_TRUE(r.contains("stats") && r["stats"].contains("fragments_culled_early"));
      culled += r["stats"]["fragments_culled_early"].get<uint64_t>();
      EXPECT_LE(estimate_bound(scene, cfg), r["stats"]["cycles"].get<uint64_t>());
    }
  EXPECT_GT(culled, 5000u);  // the scenes exercise the cull
}

// Every render stat, the memory clients' counts included, equals the reference's run
// with the memory system: the early test's depth reads are made at the ROP's port in
// the reference's order (compare_with_reference renders without memory, so here the
// reference runs with it). Textured (boxT) and untextured, one sample and 4x msaa.
TEST(ScEarlyZ, MemoryAndTextureCountsMatchReference) {
  uint64_t culled = 0, saved = 0;
  const Scene box = load_obj(kData + "/boxT.obj", obj_placement_from_config(Config{}));
  for (int k = 0; k < 4; ++k) {
    const bool textured = k < 2;
    const Scene scene = textured ? box : random_scene(7 + uint64_t(k), 96, 80, 80);
    std::vector<std::string> sets = {"depth.early=true", "raster.depth_func=less", "memory.model=dram"};
    if (k % 2) sets.push_back("raster.samples=4");
    SCOPED_TRACE(std::string(textured ? "boxT" : "random") + (k % 2 ? " msaa" : ""));
    const Config cfg = make_config(sets);
    const nlohmann::json r = run_isolated([&] { return diff_render_stats_with_memory(scene, cfg); });
    ASSERT_FALSE(r.contains("error")) << r["error"];
    EXPECT_TRUE(r["ref"].contains("memory"));
    EXPECT_TRUE(r["diff"].empty()) << r["diff"].dump();
    culled += r["ref"]["fragments_culled_early"].get<uint64_t>();
    saved += r["ref"]["texture_samples_saved"].get<uint64_t>();
  }
  EXPECT_GT(culled, 0u);
  EXPECT_GT(saved, 0u);  // the box's hidden faces were textured
}

// d full-screen layers (two triangles each) at depths 0.1, 0.2, ... drawn front to back;
// `texture`: each layer textured with it (s, t 0 to 1 across the screen).
Scene layers_front_to_back(int w, int h, int d, const std::string& texture) {
  std::string t = "viewport " + std::to_string(w) + " " + std::to_string(h) + "\n";
  if (!texture.empty()) t += "texture 1 " + texture + "\ntexfilter trilinear\nmipmap on\nbindtexture 1\n";
  const std::string W = std::to_string(w), H = std::to_string(h);
  for (int k = 0; k < d; ++k) {  // a strip of 4 vertices: the screen's two triangles
    t += "color " + std::to_string(30 * k) + " 100 200\ndepth " + std::to_string(0.1 * (k + 1)) + "\nstrip\n";
    for (const auto& [x, y, s, u] : std::vector<std::array<std::string, 4>>{
             {"0", "0", "0", "0"}, {W, "0", "1", "0"}, {"0", H, "0", "1"}, {W, H, "1", "1"}})
      t += (texture.empty() ? "" : "texcoord " + s + " " + u + "\n") + "v " + x + " " + y + "\n";
    t += "end\n";
  }
  return parse_trace(t, "layers.trace");
}

// 8 layers front to back, untextured and textured (trilinear), memory fixed and dram:
// early Z culls the 7 hidden layers' fragments; the texture stage works on one layer,
// interpolation on all eight (its lanes compute the depth the test takes, as the RTL's:
// docs/depth-culling.md "Early Z in the RTL"). Untextured, or with the DRAM, the ROP (a
// depth read a culled fragment, its fills) bounds the run, so the cycles may rise only by
// the interlock's waits (a layer's tile comes back 48 tiles later, but the diagonal's
// tiles, which both triangles of a layer cover, wait for the first's: 24734 -> 24746 with
// fixed memory, within 1 %); textured with memory.model = fixed the texture stage bounded
// it, so they drop; decoupled equals
// lock step (but textured with the DRAM, below); the figures printed are
// docs/depth-culling.md's.
TEST(ScEarlyZ, CyclesDropFrontToBackAndLockstepEqual) {
  const int w = 128, h = 96;
  for (const std::string& texture : {std::string(), kData + "/boxT.tga"})
    for (const char* memory : {"fixed", "dram"}) {
      const Scene scene = layers_front_to_back(w, h, 8, texture);
      const auto stats = [&](const char* early, bool lockstep) {
        sc::SimOptions o;
        o.lockstep = lockstep;
        const Config cfg = make_config({"raster.depth_func=less", std::string("depth.early=") + early,
                                        std::string("memory.model=") + memory});
        nlohmann::json j = run_isolated([&] {
          nlohmann::json s = simulate_stats(scene, cfg, o);
          s["estimate_bound"] = estimate_bound(scene, cfg);
          return s;
        });
        for (const char* k : {"sim_wall_seconds", "wall_seconds", "simulated_cycles_per_second"}) j.erase(k);
        return j;
      };
      SCOPED_TRACE(std::string(texture.empty() ? "untextured" : "textured") + " memory " + memory);
      const nlohmann::json off = stats("false", false), on = stats("true", false), on_lock = stats("true", true);
      ASSERT_FALSE(off.contains("error")) << off["error"];
      ASSERT_FALSE(on.contains("error")) << on["error"];
      // Textured with the DRAM, decoupled and lock step differ with early Z off as well
      // (115733 and 114148 cycles with early Z off: the texture client's fills meet the
      // ROP's requests in another order), so equality is asserted where it holds.
      if (texture.empty() || std::string(memory) == "fixed") {
        EXPECT_EQ(on, on_lock);
      }
      const uint64_t c_off = off["cycles"], c_on = on["cycles"];
      std::printf("8 layers front to back, %d x %d, %s, memory %s: %llu cycles early Z off, %llu on (%.1f %%), "
                  "interpolate busy %llu -> %llu\n",
                  w, h, texture.empty() ? "untextured" : "textured", memory, (unsigned long long)c_off,
                  (unsigned long long)c_on, 100.0 * (double(c_on) - double(c_off)) / double(c_off),
                  (unsigned long long)off["stages"]["interpolate"]["busy"].get<uint64_t>(),
                  (unsigned long long)on["stages"]["interpolate"]["busy"].get<uint64_t>());
      EXPECT_EQ(on["stages"]["interpolate"]["busy"].get<uint64_t>(), off["stages"]["interpolate"]["busy"].get<uint64_t>());
      if (texture.empty()) EXPECT_LE(c_on, c_off + c_off / 100);  // the ROP's bound, the interlock's waits
      else if (std::string(memory) == "dram") EXPECT_LE(c_on, c_off);  // the DRAM's bound
      else EXPECT_LT(c_on, c_off);
      EXPECT_EQ(on["fragments_culled_early"].get<uint64_t>(), 7u * uint64_t(w * h));  // every hidden fragment
      EXPECT_EQ(on["framebuffer_crc32"], off["framebuffer_crc32"]);
      EXPECT_GE(c_on, on["estimate_bound"].get<uint64_t>());
      EXPECT_GE(c_off, off["estimate_bound"].get<uint64_t>());
    }
}

}  // namespace
}  // namespace rastsim::sctest
