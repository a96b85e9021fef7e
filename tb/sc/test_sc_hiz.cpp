// SPDX-License-Identifier: Apache-2.0
// Hi-Z in the timed model (depth.hiz, docs/depth-culling.md, "The timed model"): coarse
// raster culls the tiles the reference culls, with the same counts, image, fragment
// stream and depth buffer; the cycles stay above the analytic lower bound and equal in
// lock step; and they drop on a scene drawn front to back.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "config/memory_config.h"
#include "config/raster_state_config.h"
#include "report/stats_json.h"
#include "scene_test.h"
#include "sim_harness.h"

namespace rastsim::sctest {
namespace {

// Seeded random scenes (mid-stream depth clears, scissor, viewport change) under every
// mode, block size and a depth function of each direction, tiles of 8 and 16, the table
// on chip and spilled: the timed model matches the reference stat for stat (Hi-Z keys
// included), fragment for fragment, and its cycles are >= the estimate's bound.
TEST(ScHiz, MatchesReferenceOnRandomScenes) {
  uint64_t culled = 0, accepted = 0, seed = 0;
  for (const char* mode : {"max", "minmax"})
    for (const char* block : {"4", "8", "16"})
      for (const char* func : {"less", "lequal", "greater"}) {
        ++seed;
        const std::vector<std::string> sets = {std::string("raster.depth_func=") + func,
                                               std::string("depth.hiz=") + mode,
                                               std::string("depth.hiz_block=") + block,
                                               seed % 2 ? "depth.hiz_bytes=64" : "depth.hiz_bytes=1048576",
                                               seed % 3 ? "raster.tile_size=16" : "raster.tile_size=8"};
        SCOPED_TRACE(std::string(mode) + " block " + block + " " + func);
        const Config cfg = make_config(sets);
        const nlohmann::json r = run_isolated([&] { return compare_with_reference(random_scene(seed, 96, 80, 80), cfg); });
        expect_matches_reference(r);
        if (r.contains("stats") && r["stats"].contains("tiles_culled_hiz")) {
          culled += r["stats"]["tiles_culled_hiz"].get<uint64_t>();
          accepted += r["stats"]["tiles_accepted_hiz"].get<uint64_t>();
        } else {
          ADD_FAILURE() << "no Hi-Z keys in the timed model's stats";
        }
      }
  EXPECT_GT(culled, 50u);  // the scenes exercise the cull and the accept
  EXPECT_GT(accepted, 10u);
}

// With the memory system (memory.model = dram) every render stat, the memory clients'
// counts included, equals the reference's: minmax's accepted tiles read no depth in
// either model (compare_with_reference renders without the memory system, so the
// reference runs here with it).
TEST(ScHiz, MemoryCountsMatchReference) {
  uint64_t accepted = 0;
  for (const char* mode : {"max", "minmax"})
    for (uint64_t seed : {3u, 4u}) {
      SCOPED_TRACE(std::string(mode) + " seed " + std::to_string(seed));
      const Config cfg = make_config({"raster.depth_func=less", std::string("depth.hiz=") + mode, "memory.model=dram",
                                      seed == 3 ? "depth.hiz_bytes=64" : "depth.hiz_bytes=1048576"});
      const Scene scene = random_scene(seed, 96, 80, 80);
      const nlohmann::json r = run_isolated([&] { return diff_render_stats_with_memory(scene, cfg); });
      ASSERT_FALSE(r.contains("error")) << r["error"];
      EXPECT_TRUE(r["ref"].contains("memory"));
      EXPECT_TRUE(r["diff"].empty()) << r["diff"].dump();
      accepted += r["ref"]["tiles_accepted_hiz"].get<uint64_t>();
    }
  EXPECT_GT(accepted, 0u);
}

// A Hi-Z decision's tile, the same at both levels: the footprint and its triangle.
using TileKey = std::tuple<int, int, int, int, int64_t, int64_t, std::array<int64_t, 3>, std::array<int64_t, 3>,
                           std::array<uint32_t, 3>>;
TileKey tile_key(const SetupTriangle& t, const PixelRect& fp) {
  return {fp.x0, fp.y0, fp.x1, fp.y1, t.origin_x, t.origin_y, t.x, t.y, t.z};
}

// depth.hiz_sync = lagged on one scene: the reference's culls and accepts (render, a
// zero-lag table) and the timed model's; `bug` plants an accept on busy blocks. Counts
// the timed model's culls and accepts that are not the reference's (each matched once).
nlohmann::json lagged_run(const Scene& scene, const Config& cfg, bool bug) {
  std::multiset<TileKey> ref_culled, ref_accepted;
  RenderStats ref_stats;
  SceneRenderer renderer(raster_state_from_config(cfg), ref_stats);
  renderer.set_hiz_observer([&](const HizEvent& e) {
    (e.decision == HizDecision::Culled ? ref_culled : ref_accepted).insert(tile_key(e.tri, e.footprint));
  });
  renderer.run(scene.commands);
  const Framebuffer ref_fb = renderer.finish();
  uint64_t foreign_culls = 0, foreign_accepts = 0;
  sc::SimOptions o;
  o.hiz_lag_accept_busy = bug;
  o.on_hiz = [&](const SetupTriangle& t, const PixelRect& fp, HizDecision d) {
    std::multiset<TileKey>& ref = d == HizDecision::Culled ? ref_culled : ref_accepted;
    const auto it = ref.find(tile_key(t, fp));
    if (it == ref.end()) ++(d == HizDecision::Culled ? foreign_culls : foreign_accepts);
    else ref.erase(it);
  };
  const sc::SimResult r = sc::simulate_scene(scene, ArchParams::resolve(cfg), o);
  return {{"crc_ref", ref_fb.color_crc32()}, {"crc_sim", r.fb.color_crc32()}, {"depth_equal", ref_fb.same_depth(r.fb)},
          {"culled_ref", ref_stats.hiz.tiles_culled}, {"culled_sim", r.render.hiz.tiles_culled},
          {"accepted_ref", ref_stats.hiz.tiles_accepted}, {"accepted_sim", r.render.hiz.tiles_accepted},
          {"tested_ref", ref_stats.hiz.tiles_tested}, {"tested_sim", r.render.hiz.tiles_tested},
          {"passed_ref", ref_stats.fragments_passed}, {"passed_sim", r.render.fragments_passed},
          {"foreign_culls", foreign_culls}, {"foreign_accepts", foreign_accepts}, {"stats", r.to_json()}};
}

// depth.hiz_sync = lagged (docs/depth-culling.md "Lagged"): random scenes (clears,
// scissor, viewport changes) under every mode and handled depth function, blocks of 4 and
// 8, tiles of 8 and 16, the table on chip and mostly spilled (256 bytes).
// The image and depth buffer are the reference's; every tile the timed model culls or
// accepts is one the reference culls or accepts (so its counts are at most render's);
// the planted bug (an accept on blocks a tile in flight touches) must break one of these.
TEST(ScHiz, LaggedDecisionsSubsetOfReference) {
  uint64_t seed = 100, culled_ref = 0, culled_sim = 0, accepted_ref = 0, accepted_sim = 0, bug_caught = 0;
  for (const char* mode : {"max", "minmax"})
    for (const char* func : {"less", "lequal", "greater", "gequal"})
      for (const char* block : {"4", "8"}) {
        if (std::string(mode) == "max" && func[0] == 'g') continue;  // max handles less, lequal only
        ++seed;
        const Config cfg = make_config({std::string("raster.depth_func=") + func, std::string("depth.hiz=") + mode,
                                        std::string("depth.hiz_block=") + block, "depth.hiz_sync=lagged",
                                        seed % 3 == 0 ? "depth.hiz_bytes=256" : "depth.hiz_bytes=1048576",
                                        seed % 2 ? "raster.tile_size=16" : "raster.tile_size=8"});
        SCOPED_TRACE(std::string(mode) + " " + func + " block " + block + " seed " + std::to_string(seed));
        const Scene scene = random_scene(seed, 96, 80, 120);
        const nlohmann::json r = run_isolated([&] { return lagged_run(scene, cfg, false); });
        ASSERT_FALSE(r.contains("error")) << r["error"];
        EXPECT_EQ(r["crc_sim"], r["crc_ref"]);
        EXPECT_TRUE(r["depth_equal"].get<bool>());
        EXPECT_EQ(r["passed_sim"], r["passed_ref"]);
        EXPECT_EQ(r["tested_sim"], r["tested_ref"]);
        EXPECT_EQ(r["foreign_culls"], 0u);
        EXPECT_EQ(r["foreign_accepts"], 0u);
        EXPECT_LE(r["culled_sim"].get<uint64_t>(), r["culled_ref"].get<uint64_t>());
        EXPECT_LE(r["accepted_sim"].get<uint64_t>(), r["accepted_ref"].get<uint64_t>());
        EXPECT_GE(r["stats"]["cycles"].get<uint64_t>(), r["stats"]["cycles_lower_bound"].get<uint64_t>());
        culled_ref += r["culled_ref"].get<uint64_t>(), culled_sim += r["culled_sim"].get<uint64_t>();
        accepted_ref += r["accepted_ref"].get<uint64_t>(), accepted_sim += r["accepted_sim"].get<uint64_t>();
        const nlohmann::json b = run_isolated([&] { return lagged_run(scene, cfg, true); });
        ASSERT_FALSE(b.contains("error")) << b["error"];
        if (b["foreign_accepts"].get<uint64_t>() > 0 || b["crc_sim"] != b["crc_ref"] || !b["depth_equal"].get<bool>())
          ++bug_caught;
      }
  std::printf("lagged: culled %llu of the reference's %llu, accepted %llu of %llu; the planted bug caught in %llu "
              "scenes of 12\n",
              (unsigned long long)culled_sim, (unsigned long long)culled_ref, (unsigned long long)accepted_sim,
              (unsigned long long)accepted_ref, (unsigned long long)bug_caught);
  EXPECT_GT(culled_sim, 50u);  // the scenes exercise the lagged cull and accept
  EXPECT_GT(accepted_sim, 10u);
  EXPECT_LT(culled_sim + accepted_sim, culled_ref + accepted_ref);  // and the lag (busy blocks) shows
  EXPECT_GT(bug_caught, 0u);
}

// d full-screen layers (two triangles each) at depths 0.1, 0.2, ... drawn front to back.
Scene layers_front_to_back(int w, int h, int d) {
  Scene scene;
  scene.commands.push_back({CmdViewport{w, h}, {"layers", 1}});
  for (int k = 0; k < d; ++k) {
    const double z = 0.1 * (k + 1);
    const auto v = [&](double x, double y) { return scene_test::screen_vertex(x, y, z, uint8_t(30 * k)); };
    CmdPrimitives p;
    p.vertices = {v(0, 0), v(w, 0), v(0, h), v(w, 0), v(w, h), v(0, h)};
    scene.commands.push_back({p, {"layers", 2 + k}});
  }
  return scene;
}

// 8 layers front to back: Hi-Z culls every tile of the 7 hidden layers, so fine raster,
// interpolation and the ROP see one layer's work; the cycles must drop, decoupled equal
// to lock step.
TEST(ScHiz, CyclesDropFrontToBackAndLockstepEqual) {
  const Scene scene = layers_front_to_back(128, 96, 8);
  const auto stats = [&](const char* mode, bool lockstep, const char* sync = "interlock") {
    sc::SimOptions o;
    o.lockstep = lockstep;
    const Config cfg = make_config({"raster.depth_func=less", std::string("depth.hiz=") + mode,
                                    std::string("depth.hiz_sync=") + sync});
    nlohmann::json j = run_isolated([&] { return simulate_stats(scene, cfg, o); });
    for (const char* k : {"sim_wall_seconds", "wall_seconds", "simulated_cycles_per_second"}) j.erase(k);
    return j;
  };
  const nlohmann::json off = stats("off", false), max = stats("max", false), max_lock = stats("max", true);
  ASSERT_FALSE(off.contains("error")) << off["error"];
  ASSERT_FALSE(max.contains("error")) << max["error"];
  EXPECT_EQ(max, max_lock);
  const uint64_t c_off = off["cycles"], c_max = max["cycles"];
  std::printf("8 layers front to back, 128 x 96: %llu cycles Hi-Z off, %llu max (%llu tiles culled)\n",
              (unsigned long long)c_off, (unsigned long long)c_max,
              (unsigned long long)max["tiles_culled_hiz"].get<uint64_t>());
  EXPECT_LT(c_max, c_off);
  EXPECT_EQ(max["fragments_culled_hiz"].get<uint64_t>(), 7u * 128u * 96u);  // every hidden fragment
  EXPECT_GE(c_max, max["cycles_lower_bound"].get<uint64_t>());
  // Lagged (depth.hiz_sync): its decisions depend on the model's cycles, not on how far
  // the stages run ahead of each other, so decoupled equals lock step too.
  const nlohmann::json lag = stats("max", false, "lagged"), lag_lock = stats("max", true, "lagged");
  ASSERT_FALSE(lag.contains("error")) << lag["error"];
  EXPECT_EQ(lag, lag_lock);
  std::printf("the same, lagged: %llu cycles (%llu tiles culled)\n", (unsigned long long)lag["cycles"].get<uint64_t>(),
              (unsigned long long)lag["tiles_culled_hiz"].get<uint64_t>());
  EXPECT_LE(lag["tiles_culled_hiz"].get<uint64_t>(), max["tiles_culled_hiz"].get<uint64_t>());
  EXPECT_EQ(lag["framebuffer_crc32"], max["framebuffer_crc32"]);
}

// The spilled table through the timed memory system (memory.model = dram, client hiz,
// timing/hiz_memory_port.h): 8 layers front to back with the whole table spilled
// (depth.hiz_bytes = 0) make exactly the reference's entry bytes as DRAM requests (one
// burst each: entries of 16 bytes); the walk's stalls make the run slower than with the
// table on chip, whose client makes no request; the images and every render stat but the
// table's traffic are the same.
TEST(ScHiz, SpilledTableTimedThroughMemory) {
  const Scene scene = layers_front_to_back(128, 96, 8);
  const auto run = [&](const char* bytes) {
    const Config cfg = make_config({"raster.depth_func=less", "depth.hiz=max", "memory.model=dram",
                                    std::string("depth.hiz_bytes=") + bytes});
    return run_isolated([&] {
      RenderStats ref;
      render_scene(scene, raster_state_from_config(cfg), ref, {}, Framebuffer::kDefaultTileLog2, 1,
                   memory_params_from_config(cfg));
      nlohmann::json j = simulate_stats(scene, cfg);
      j["ref"] = to_json(ref);
      return j;
    });
  };
  const nlohmann::json spilled = run("0"), onchip = run("1048576");
  ASSERT_FALSE(spilled.contains("error")) << spilled["error"];
  ASSERT_FALSE(onchip.contains("error")) << onchip["error"];
  const nlohmann::json& hiz = spilled["memory"]["clients"]["hiz"];
  const uint64_t read = spilled["ref"]["hiz_dram_bytes_read"], written = spilled["ref"]["hiz_dram_bytes_written"];
  std::printf("8 layers, 128 x 96, table spilled: %llu bytes read, %llu written, %llu stall cycles; "
              "%llu cycles (on chip: %llu)\n",
              (unsigned long long)read, (unsigned long long)written,
              (unsigned long long)hiz["stall_cycles"].get<uint64_t>(),
              (unsigned long long)spilled["cycles"].get<uint64_t>(), (unsigned long long)onchip["cycles"].get<uint64_t>());
  EXPECT_GT(read, 0u);
  EXPECT_GT(written, 0u);
  EXPECT_EQ(hiz["bytes_read"].get<uint64_t>(), read);  // the functional count, as render's
  EXPECT_EQ(hiz["bytes_written"].get<uint64_t>(), written);
  EXPECT_EQ(hiz["reads"].get<uint64_t>() * 16, read);  // 16-byte entries (24-bit depth, 8 px blocks)
  EXPECT_EQ(hiz["writes"].get<uint64_t>() * 16, written);
  EXPECT_EQ(hiz["bursts_read"], hiz["reads"]);  // each entry one request of one burst
  EXPECT_EQ(hiz["bursts_written"], hiz["writes"]);
  EXPECT_GT(hiz["stall_cycles"].get<uint64_t>(), 0u);
  EXPECT_GT(spilled["cycles"].get<uint64_t>(), onchip["cycles"].get<uint64_t>());
  EXPECT_FALSE(onchip["memory"]["clients"].contains("hiz") && onchip["memory"]["clients"]["hiz"].contains("reads"));
  EXPECT_EQ(spilled["dram_bytes_read"], spilled["ref"]["dram_bytes_read"]);
  EXPECT_EQ(spilled["framebuffer_crc32"], onchip["framebuffer_crc32"]);
  EXPECT_EQ(spilled["tiles_culled_hiz"], onchip["tiles_culled_hiz"]);
  EXPECT_GE(spilled["cycles"].get<uint64_t>(), spilled["cycles_lower_bound"].get<uint64_t>());
}

}  // namespace
}  // namespace rastsim::sctest
