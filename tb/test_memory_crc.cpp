// SPDX-License-Identifier: Apache-2.0
// The functional memory system changes no image and no other stat: the shipped traces
// rendered under every combination of layout, cache geometry, fast clear and depth
// compression give the CRC and every stat of the run with memory.model = fixed; the run
// path (rop_write_run) makes the same accesses as the per-fragment path (a fragment sink
// keeps it); and the counts hold their identities (accesses = hits + misses; with no
// cache, misses = accesses).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/arch_params.h"
#include "ref/pipeline.h"
#include "report/stats_json.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

nlohmann::json stats_without_memory(RenderStats s) {
  s.memory = {};
  nlohmann::json j = to_json(s);
  j.erase("wall_seconds");
  return j;
}

struct RenderRun {
  RenderStats stats;
  uint32_t crc = 0;
};

RenderRun render(const std::string& trace, const std::vector<std::string>& sets, bool sink = false) {
  Config cfg;
  for (const std::string& kv : sets) cfg.apply_override(kv);
  const ArchParams a = ArchParams::resolve(cfg);
  const Scene scene = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/" + trace, a.placement);
  RenderRun r;
  const FragmentSink on_fragment = sink ? FragmentSink([](const Fragment&) {}) : FragmentSink();
  render_scene(scene, a.raster, r.stats, on_fragment, Framebuffer::kDefaultTileLog2, 1, a.memory);
  r.crc = r.stats.framebuffer_crc32;
  return r;
}

TEST(MemoryCrc, EverySettingKeepsTheImageAndStats) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> scenes = {
      {"torus.trace", {"raster.depth_func=less"}},
      {"primitives.trace", {}},
      {"state.trace", {"raster.depth_func=lequal"}},
      {"aa/thin.trace", {"raster.samples=4", "raster.depth_func=less"}},
  };
  const std::vector<std::vector<std::string>> layouts = {
      {"memory.fb_layout=linear"}, {"memory.fb_layout=tiled"},
      {"memory.fb_layout=tiled", "memory.fb_tile_width=16", "memory.fb_tile_height=4"}};
  const std::vector<std::vector<std::string>> caches = {
      {"rop.color_cache_bytes=0", "rop.depth_cache_bytes=0"},
      {"rop.color_cache_bytes=1024", "rop.color_cache_ways=2", "rop.color_cache_line_bytes=32",
       "rop.depth_cache_bytes=2048", "rop.depth_cache_ways=2"},
      {}};  // the defaults
  for (const auto& [trace, base] : scenes) {
    SCOPED_TRACE(trace);
    const RenderRun off = render(trace, base);
    const nlohmann::json want = stats_without_memory(off.stats);
    EXPECT_FALSE(off.stats.memory.enabled);
    for (const auto& layout : layouts)
      for (const auto& cache : caches)
        for (const char* fast : {"rop.fast_clear=false", "rop.fast_clear=true"})
          for (const char* comp : {"rop.depth_compression=none", "rop.depth_compression=plane"}) {
            std::vector<std::string> sets = base;
            for (const auto* group : {&layout, &cache})
              sets.insert(sets.end(), group->begin(), group->end());
            sets.insert(sets.end(), {"memory.model=dram", fast, comp});
            if (cache.size() == 2 && std::string(comp).ends_with("plane")) continue;  // plane needs a depth cache
            std::string what;
            for (const auto& s : sets) what += s + " ";
            SCOPED_TRACE(what);
            const RenderRun on = render(trace, sets);
            EXPECT_EQ(on.crc, off.crc);
            EXPECT_EQ(stats_without_memory(on.stats), want);
            const MemoryStats& m = on.stats.memory;
            ASSERT_TRUE(m.enabled);
            for (const MemoryClientStats* c : {&m.rop_color, &m.rop_depth}) {
              EXPECT_EQ(c->accesses, c->hits + c->misses);
              if (cache.size() == 2) {
                EXPECT_EQ(c->misses, c->accesses);
              }
            }
            EXPECT_GT(m.rop_color.accesses, 0u);
          }
  }
}

TEST(MemoryCrc, RunPathMakesTheSameAccessesAsThePerFragmentPath) {
  for (const char* trace : {"torus.trace", "primitives.trace"})
    for (const char* func : {"raster.depth_func=less", "raster.depth_func=always"}) {
      SCOPED_TRACE(std::string(trace) + " " + func);
      const std::vector<std::string> sets = {func, "memory.model=dram", "memory.fb_layout=tiled", "rop.fast_clear=true",
                                             "rop.depth_compression=plane"};
      const nlohmann::json run = to_json(render(trace, sets).stats), each = to_json(render(trace, sets, true).stats);
      // The public keys (docs/stats.md), and equal on both paths.
      for (const char* key : {"dram_bytes_read", "dram_bytes_written", "rop_color_cache_hits", "rop_color_cache_misses",
                              "rop_depth_cache_hits", "rop_depth_cache_misses", "fast_clear_blocks",
                              "depth_compressed_bytes"}) {
        ASSERT_TRUE(run.contains(key)) << key;
        EXPECT_EQ(run[key], each[key]) << key;
      }
      for (const char* client : {"rop_color", "rop_depth"}) {
        ASSERT_TRUE(run["memory"]["clients"].contains(client)) << client;
        EXPECT_GT(run["memory"]["clients"][client]["accesses"].get<uint64_t>(), 0u);
      }
      EXPECT_EQ(run["memory"], each["memory"]);
    }
}

TEST(MemoryCrc, BadGeometryIsAConfigError) {
  for (const char* kv : {"rop.color_cache_bytes=1000", "rop.depth_cache_bytes=3072"}) {
    Config cfg;
    cfg.apply_override(kv);
    EXPECT_THROW(ArchParams::resolve(cfg), ConfigError) << kv;
  }
  Config plane;
  plane.apply_override("rop.depth_compression=plane");
  plane.apply_override("rop.depth_cache_bytes=0");
  EXPECT_THROW(ArchParams::resolve(plane), ConfigError);
  Config overlap;
  overlap.apply_override("memory.depth_base=4096");
  EXPECT_NO_THROW(ArchParams::resolve(overlap));  // memory.model = fixed: no addresses
  overlap.apply_override("memory.model=dram");
  EXPECT_THROW(ArchParams::resolve(overlap), ConfigError);
}

}  // namespace
}  // namespace rastsim
