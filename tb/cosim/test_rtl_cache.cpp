// SPDX-License-Identifier: Apache-2.0
// The on-demand RTL path without a build (the build itself: test_rtl_cache.sh, label
// rtlbuild): the runner's request carries a config exactly (every value and origin, floats
// to the bit), the CosimResult survives its JSON, and a config the RTL cannot run (a
// method it lacks, a tile whose sample mask Verilator refuses), or an in-memory scene on a
// config no shipped model fits, fails before any build with a message naming the config
// and the key; memory.model = "dram" runs on a shipped model with the reference's memory
// counts.
#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>

#include "ref/pipeline.h"
#include "rtlsim/cosim.h"
#include "rtlsim/cosim_setup.h"
#include "scene/scene_io.h"
#include "cosim_test_util.h"

namespace rastsim::rtlsim {
namespace {

TEST(RtlRunnerRequest, CarriesEveryConfigValueAndOrigin) {
  Config cfg = load_shipped_config("embedded");
  // A float with every digit significant, and a value with a space.
  cfg.apply_override("clock.core_mhz=123.45678901234567");
  cfg.validate();
  Scene scene;
  scene.source = "scene.trace";
  scene.commands.resize(3);
  CosimOptions o;
  o.tile_size = 4;
  o.backpressure = 0.25;
  o.stress_seed = 7;
  o.fst_path = "w.fst";
  const RunnerRequest q = read_runner_request(nlohmann::json::parse(runner_request(scene, ArchParams::resolve(cfg), o).dump()));
  ASSERT_EQ(q.config.values().size(), cfg.values().size());
  for (const auto& [key, v] : cfg.values()) {
    SCOPED_TRACE(key);
    EXPECT_TRUE(q.config.get(key) == v) << to_string(q.config.get(key)) << " != " << to_string(v);
    EXPECT_EQ(q.config.origin(key), cfg.origin(key));
  }
  EXPECT_EQ(q.config.get_float("clock.core_mhz"), 123.45678901234567);
  EXPECT_EQ(q.scene, "scene.trace");
  EXPECT_EQ(q.scene_commands, 3u);
  EXPECT_EQ(q.options.tile_size, 4);
  EXPECT_EQ(q.options.backpressure, 0.25);
  EXPECT_EQ(q.options.stress_seed, 7u);
  EXPECT_EQ(q.options.fst_path, "w.fst");
  EXPECT_EQ(q.options.max_cycles, o.max_cycles);
}

TEST(RtlRunnerResult, EveryFieldSurvivesJson) {
  CosimResult r;
  r.rtl_config = "cache:0123456789abcdef";
  r.rtl_model_dir = "/c/0123456789abcdef";
  r.rtl_cache_hit = true;
  r.rtl_build_seconds = 1.5;
  r.cycles_rtl = 1001;
  r.fragments_expected = 1002;
  r.fragments_compared = 1003;
  r.mismatches = 4;
  r.first_mismatch = "fragment #5";
  r.triangles = 6;
  r.markers = 7;
  r.commands_2d = 8;
  r.pixels_2d = 9;
  r.crc_rtl = 0xdeadbeef;
  r.crc_ref = 0xcafef00d;
  r.samples = 4;
  r.rop_accesses = 10;
  r.resolve_cycles = 11;
  r.wall_seconds = 0.125;
  r.memory.enabled = true;
  r.memory.rop_depth.misses = 12;
  r.memory.rop_color.compressed_bytes = 13;
  r.dram = {{"dram_row_hit_rate", 0.5}};
  const nlohmann::json j = r;
  const CosimResult b = nlohmann::json::parse(j.dump()).get<CosimResult>();
  EXPECT_EQ(nlohmann::json(b), j);
  EXPECT_EQ(b.crc_rtl, 0xdeadbeefu);
  EXPECT_EQ(b.first_mismatch, "fragment #5");
  EXPECT_TRUE(b.rtl_cache_hit);
  EXPECT_EQ(b.memory.rop_depth.misses, 12u);
  EXPECT_EQ(b.dram["dram_row_hit_rate"], 0.5);
  // A field the runner does not send keeps its default.
  EXPECT_EQ(nlohmann::json::object().get<CosimResult>().samples, 1);
}

// run_cosim's error on an in-memory scene with the embedded config and these --sets.
std::string cosim_error(std::initializer_list<std::string> sets) {
  Config cfg = load_shipped_config("embedded");
  for (const std::string& set : sets) cfg.apply_override(set);
  cfg.validate();
  try {
    run_cosim(parse_trace("viewport 64 64\ntri 0 0 8 0 0 8\n", "mem.trace"), ArchParams::resolve(cfg));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}
std::string cosim_error(const std::string& set) { return cosim_error({set}); }

TEST(RtlOnDemand, ConfigTheRtlCannotRunNamesTheKey) {
  const std::string m = cosim_error("raster.traversal=bbox");
  EXPECT_NE(m.find("--set raster.traversal=bbox: raster.traversal = bbox has no RTL"), std::string::npos) << m;
}

// Depth culling the RTL lacks is refused by its key (the SystemC model would cull what the
// RTL draws, so the cycles would compare two machines): a Hi-Z table with no entry on chip
// (rast_top_hiz keeps at least one; the rest go through the hiz port), early Z with an
// applied Hi-Z (rast_early_z does not take Hi-Z's accepts), and depth.hiz_sync = lagged
// with spilled entries (rast_top_hiz's Lagged is built for the table on chip: the lagged
// ctests, cosim.hiz.lagged.*). Hi-Z that does not apply (depth.func always) is the
// Hi-Z-off run and runs on the shipped model.
TEST(RtlOnDemand, DepthCullingTheRtlLacksNamesTheKey) {
  for (const char* mode : {"max", "minmax"}) {
    const std::string m = cosim_error({std::string("depth.hiz=") + mode, "depth.hiz_bytes=0"});
    EXPECT_NE(m.find("--set depth.hiz_bytes=0: depth.hiz_bytes = 0 holds none of the display's "), std::string::npos)
        << m;
    EXPECT_NE(m.find("the RTL keeps at least one entry on chip"), std::string::npos) << m;
  }
  const std::string e = cosim_error({"depth.early=true", "depth.hiz=max", "raster.depth_func=less"});
  EXPECT_NE(e.find("--set depth.early=true: depth.early = true co-simulates without an applied depth.hiz"),
            std::string::npos) << e;
  EXPECT_EQ(cosim_error({"depth.hiz=max", "raster.depth_func=always"}), "(no error)");
  const std::string l =
      cosim_error({"depth.hiz=max", "raster.depth_func=less", "depth.hiz_sync=lagged", "depth.hiz_bytes=16"});
  EXPECT_NE(l.find("--set depth.hiz_sync=lagged: depth.hiz_sync = lagged with spilled Hi-Z entries (--set "
                   "depth.hiz_bytes=16: depth.hiz_bytes = 16 holds 1 of the display"),
            std::string::npos) << l;
  EXPECT_NE(l.find("has no RTL yet"), std::string::npos) << l;
  // Where Hi-Z does not apply the key changes nothing, and the run goes on.
  EXPECT_EQ(cosim_error({"depth.hiz=max", "raster.depth_func=always", "depth.hiz_sync=lagged"}), "(no error)");
}

// memory.model = "dram" on a shipped model (memory needs no RTL parameter): the RTL ROP's
// port served by the timed memory system, 0 mismatches, and every functional count
// (hits, misses, evictions, bytes of both clients) equal to the reference's (render_scene
// with the same memory settings: the reference pipeline, not the testbench's replay).
// Small caches, fast clear and plane compression, depth test on: evictions, compressed
// write-backs (read from the replayed framebuffer) and fills all happen; with random
// backpressure on the port too.
TEST(RtlOnDemand, DramMemoryCountsEqualTheReference) {
  Config cfg = load_shipped_config("embedded");
  for (const char* kv : {"memory.model=dram", "raster.depth_func=less", "rop.color_cache_bytes=1024",
                         "rop.depth_cache_bytes=2048", "rop.fast_clear=true", "rop.depth_compression=plane"})
    cfg.apply_override(kv);
  cfg.validate();
  const ArchParams a = ArchParams::resolve(cfg);
  const Scene scene = random_scene(cfg, 0xd4a3u, 120);
  RenderStats ref;
  render_scene(scene, a.raster, ref, {}, Framebuffer::kDefaultTileLog2, 1, a.memory);
  ASSERT_TRUE(ref.memory.enabled);
  EXPECT_GT(ref.memory.rop_depth.evictions, 0u);
  EXPECT_GT(ref.memory.rop_depth.compressed_blocks, 0u);
  for (const double backpressure : {0.0, 0.3}) {
    SCOPED_TRACE(backpressure);
    CosimOptions o;
    o.backpressure = backpressure;
    o.stress_seed = 5;
    const CosimResult r = run_cosim(scene, a, o);
    expect_clean(r);
    EXPECT_EQ(r.crc_rtl, r.crc_ref);
    EXPECT_EQ(nlohmann::json(r.memory), nlohmann::json(ref.memory));
    // The DRAM moved what the functional model counts (64-byte bursts: the reads' bursts
    // cover the bytes read).
    const nlohmann::json j = r.to_json(o);
    EXPECT_EQ(j["dram_bytes_read"], ref.memory.rop_color.bytes_read + ref.memory.rop_depth.bytes_read);
    EXPECT_GE(j["memory"]["dram"]["bytes_read"].get<uint64_t>(), j["dram_bytes_read"].get<uint64_t>());
    EXPECT_GT(j["memory"]["clients"]["rop_depth"]["bursts_read"].get<uint64_t>(), 0u);
  }
}

TEST(RtlOnDemand, InMemorySceneOnANewConfigNamesConfigAndScene) {
  const std::string m = cosim_error("fifo.tile_depth=3");
  EXPECT_NE(m.find("embedded.toml --set fifo.tile_depth=3"), std::string::npos) << m;
  EXPECT_NE(m.find("'mem.trace' is not a file"), std::string::npos) << m;
}

TEST(RtlOnDemand, TileTooLargeForVerilatorNamesTileSizeAndSamples) {
  // 128 x 128 px x 2 samples (the RTL's minimum MaxSamples) = 32768 mask bits > 8192.
  Config cfg = load_shipped_config("embedded");
  cfg.apply_override("raster.tile_size=128");
  cfg.validate();
  try {
    prepare_rtl_model(ArchParams::resolve(cfg));
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("raster.tile_size = 128 (--set raster.tile_size=128) with raster.samples = 1 needs a "
                     "32768-bit sample mask"),
              std::string::npos)
        << m;
  }
}

}  // namespace
}  // namespace rastsim::rtlsim
