// SPDX-License-Identifier: Apache-2.0
// The ROP caches' counts (ref/memory/cache.h, surface_client.h) against
// - a 2-way cache and a seven-access stream worked by hand, its counts and the address
//   and size of every transfer (fills, the write-back at the evicted line, the flush);
// - an independent brute-force model written here (a list of lines a set, most recently
//   used first) on random streams and on the access stream of a real scene (the torus,
//   the reference ROP's accesses recorded through SurfaceClient::on_access), and the
//   pipeline's own counts of that scene equal to the recorded stream's;
// - the 2D engine's spans and blits through the colour cache, worked by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <list>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "config/arch_params.h"
#include "ref/memory/rop_memory.h"
#include "ref/pipeline.h"
#include "ref/rop.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

// The brute-force cache: per set a list of (line, dirty), most recently used first; a
// miss pushes to the front and, when the set is full, drops the back.
struct BruteCache {
  uint64_t sets, ways, line_bytes;
  std::vector<std::list<std::pair<uint64_t, bool>>> lists;
  MemoryClientStats st;
  BruteCache(uint64_t bytes, uint64_t w, uint64_t line) : sets(bytes / (w * line)), ways(w), line_bytes(line), lists(sets) {}
  void access(uint64_t offset, bool write) {
    const uint64_t line = offset / line_bytes;
    auto& l = lists[line % sets];
    ++st.accesses;
    auto it = std::find_if(l.begin(), l.end(), [&](const auto& e) { return e.first == line; });
    if (it != l.end()) {
      ++st.hits;
      const bool dirty = it->second || write;
      l.erase(it);
      l.push_front({line, dirty});
      return;
    }
    ++st.misses;
    st.bytes_read += line_bytes;
    if (l.size() == ways) {
      ++st.evictions;
      if (l.back().second) {
        ++st.writebacks;
        st.bytes_written += line_bytes;
      }
      l.pop_back();
    }
    l.push_front({line, write});
  }
  void flush() {
    for (auto& l : lists)
      for (auto& e : l)
        if (e.second) {
          ++st.writebacks;
          st.bytes_written += line_bytes;
          e.second = false;
        }
  }
  void drop() {
    for (auto& l : lists) l.clear();
  }
};

void expect_same(const MemoryClientStats& got, const MemoryClientStats& want) {
  EXPECT_EQ(got.accesses, want.accesses);
  EXPECT_EQ(got.hits, want.hits);
  EXPECT_EQ(got.misses, want.misses);
  EXPECT_EQ(got.evictions, want.evictions);
  EXPECT_EQ(got.writebacks, want.writebacks);
  EXPECT_EQ(got.bytes_read, want.bytes_read);
  EXPECT_EQ(got.bytes_written, want.bytes_written);
}

TEST(MemoryCache, TwoWayStreamByHand) {
  // 2 ways x 2 sets x 16-byte lines = 64 bytes; set = line mod 2. The surface is 32 x 2
  // pixels, linear, 4 bytes: pixel (4 n, 0) is the first sample of line n.
  //   1 R line 0: miss, set 0 = {0}                     read 16
  //   2 W line 2: miss, set 0 = {2*, 0}                 read 16
  //   3 R line 0: hit,  set 0 = {0, 2*}
  //   4 R line 4: miss, evicts LRU 2 (dirty)            read 16, write back 16
  //   5 W line 1: miss, set 1 = {1*}                    read 16
  //   6 R line 2: miss, evicts LRU 0 (clean)            read 16
  //   7 W line 4: hit,  set 0 = {4*, 2}
  //   flush: lines 1 and 4 dirty                        write back 2 x 16
  // accesses 7, hits 2, misses 5, evictions 2, writebacks 3, read 80, written 48.
  SurfaceClient c(SurfaceLayout(FbLayout::Linear, 1, 1, 0, 32, 2, 1, 4), {64, 2, 16}, false, 8, 8);
  const std::pair<int, bool> stream[] = {{0, false}, {2, true}, {0, false}, {4, false}, {1, true}, {2, false}, {4, true}};
  for (const auto& [line, write] : stream) c.access(4 * line, 0, 0, write);
  c.write_back_all();
  MemoryClientStats want;
  want.accesses = 7, want.hits = 2, want.misses = 5, want.evictions = 2, want.writebacks = 3;
  want.bytes_read = 80, want.bytes_written = 48;
  expect_same(c.stats(), want);
}

TEST(MemoryCache, TakeStateCarriesLinesDirtyBitsLruAndFlags) {
  // Frame sampling's warm-up (SurfaceClient::take_state): a client that takes another's
  // state then behaves as that one would. 2 ways x 2 sets of 16-byte lines; `a` writes
  // lines 0 then 2 (both set 0, misses, read 2 x 16). `b` takes a's state and is fresh
  // in its counts: W line 0 hits (a fresh client would miss), R line 4 misses and evicts
  // the LRU line 2, dirty: written back.
  const SurfaceLayout layout(FbLayout::Linear, 1, 1, 0, 32, 2, 1, 4);
  SurfaceClient a(layout, {64, 2, 16}, false, 8, 8), b(layout, {64, 2, 16}, false, 8, 8);
  a.access(0, 0, 0, true);
  a.access(8, 0, 0, true);
  b.take_state(a);
  b.access(0, 0, 0, true);
  b.access(16, 0, 0, false);
  MemoryClientStats want;
  want.accesses = 2, want.hits = 1, want.misses = 1, want.evictions = 1, want.writebacks = 1;
  want.bytes_read = 16, want.bytes_written = 16;
  expect_same(b.stats(), want);
  // Fast-clear flags: after a's clear every block is flagged, so b's fill of line 0 is
  // made of the clear value and reads nothing (a fresh client reads 16).
  SurfaceClient fa(layout, {64, 2, 16}, true, 8, 8), fb(layout, {64, 2, 16}, true, 8, 8);
  fa.clear();
  fb.take_state(fa);
  fb.access(0, 0, 0, false);
  EXPECT_EQ(fb.stats().misses, 1u);
  EXPECT_EQ(fb.stats().bytes_read, 0u);
  // Another surface's state is refused.
  SurfaceClient other(SurfaceLayout(FbLayout::Linear, 1, 1, 4096, 32, 2, 1, 4), {64, 2, 16}, false, 8, 8);
  EXPECT_THROW(other.take_state(a), std::logic_error);
}

TEST(MemoryCache, TransfersNameTheirOwnLinesByHand) {
  // TwoWayStreamByHand's stream on a surface at base 4096: every fill at its missed line,
  // the write-back at the evicted line (line 2 = byte 32), the flush line by line in
  // set order (set 0: way 0 holds line 2, clean; way 1 line 4, dirty; set 1: line 1).
  SurfaceClient c(SurfaceLayout(FbLayout::Linear, 1, 1, 4096, 32, 2, 1, 4), {64, 2, 16}, false, 8, 8);
  std::vector<MemoryTransfer> got;
  c.on_transfer = [&](const MemoryTransfer& t) { got.push_back(t); };
  const std::pair<int, bool> stream[] = {{0, false}, {2, true}, {0, false}, {4, false}, {1, true}, {2, false}, {4, true}};
  for (const auto& [line, write] : stream) c.access(4 * line, 0, 0, write);
  c.write_back_all();
  const std::vector<std::tuple<uint64_t, uint64_t, bool>> want = {
      {4096 + 0, 16, false},  {4096 + 32, 16, false}, {4096 + 32, 16, true}, {4096 + 64, 16, false},
      {4096 + 16, 16, false}, {4096 + 32, 16, false}, {4096 + 64, 16, true}, {4096 + 16, 16, true}};
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(got[i].address, std::get<0>(want[i]));
    EXPECT_EQ(got[i].bytes, std::get<1>(want[i]));
    EXPECT_EQ(got[i].write, std::get<2>(want[i]));
  }
}

TEST(MemoryCache, NoCacheMovesEachAccessAtItsOwnSize) {
  SurfaceClient c(SurfaceLayout(FbLayout::Linear, 1, 1, 0, 8, 8, 1, 2), {0, 1, 64}, false, 8, 8);
  for (int i = 0; i < 5; ++i) c.access(i, 0, 0, false);
  for (int i = 0; i < 3; ++i) c.access(i, 1, 0, true);
  c.write_back_all();
  EXPECT_EQ(c.stats().misses, 8u);
  EXPECT_EQ(c.stats().bytes_read, 10u);
  EXPECT_EQ(c.stats().bytes_written, 6u);
}

TEST(MemoryCache, MatchesBruteForceOnRandomStreams) {
  const uint32_t seed = 0x3e3u;
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  const CacheParams geometries[] = {{64, 2, 16}, {256, 1, 32}, {1024, 4, 64}, {512, 8, 16}, {4096, 16, 64}};
  for (const CacheParams& g : geometries) {
    SCOPED_TRACE(std::to_string(g.bytes) + " bytes, " + std::to_string(g.ways) + " ways");
    const SurfaceLayout layout(FbLayout::Tiled, 4, 4, 0, 40, 24, 1, 4);
    SurfaceClient c(layout, g, false, 8, 8);
    BruteCache b(g.bytes, uint64_t(g.ways), uint64_t(g.line_bytes));
    // Random walks with locality: mostly near the last pixel, sometimes anywhere.
    int x = 0, y = 0;
    std::uniform_int_distribution<int> pct(0, 99), step(-3, 3);
    for (int i = 0; i < 20000; ++i) {
      if (pct(rng) < 10) {
        x = std::uniform_int_distribution<int>(0, 39)(rng);
        y = std::uniform_int_distribution<int>(0, 23)(rng);
      } else {
        x = std::clamp(x + step(rng), 0, 39);
        y = std::clamp(y + step(rng), 0, 23);
      }
      const bool write = pct(rng) < 50;
      c.access(x, y, 0, write);
      b.access(layout.offset_of(x, y, 0), write);
    }
    c.write_back_all();
    b.flush();
    expect_same(c.stats(), b.st);
  }
}

// The torus drawn with a depth test; the reference ROP's access stream recorded (a
// fragment sink replays rop_write on a framebuffer of its own, in pipeline order, after
// the scene's three clears) and fed to the brute-force caches.
TEST(MemoryCache, MatchesBruteForceOnTheTorusStream) {
  Config cfg;
  for (const char* kv : {"memory.model=dram", "raster.depth_func=less", "rop.color_cache_bytes=2048",
                         "rop.color_cache_ways=2", "rop.depth_cache_bytes=1024", "rop.depth_cache_ways=4",
                         "rop.depth_cache_line_bytes=32", "memory.fb_layout=tiled"})
    cfg.apply_override(kv);
  const ArchParams a = ArchParams::resolve(cfg);
  const Scene scene = load_scene(std::string(RASTSIM_SOURCE_DIR) + "/traces/torus.trace", a.placement);
  Framebuffer fb(a.raster.fb_width, a.raster.fb_height);
  fb.clear_depth((1u << a.raster.depth_bits) - 1);  // as the pipeline starts, and cleardepth 1
  RopMemory mem(a.memory, fb, a.raster.depth_bits);
  BruteCache color(2048, 2, 64), depth(1024, 4, 32);
  uint64_t n_color = 0, n_depth = 0;
  mem.color.on_access = [&](uint64_t addr, bool w) { color.access(addr - a.memory.color_base, w), ++n_color; };
  mem.depth.on_access = [&](uint64_t addr, bool w) { depth.access(addr - a.memory.depth_base, w), ++n_depth; };
  const auto clear_depth = [&] { mem.clear_depth(), depth.drop(); };
  clear_depth();  // the pipeline's initial clear, then the scene's clear and cleardepth
  mem.clear_color(), color.drop();
  clear_depth();
  RenderStats stats;
  render_scene(scene, a.raster, stats, [&](const Fragment& f) { rop_write(fb, f, a.raster.depth_func, true, nullptr, &mem); },
               Framebuffer::kDefaultTileLog2, 1, a.memory);
  mem.finish();
  color.flush();
  depth.flush();
  ASSERT_GT(n_color, 1000u);
  ASSERT_GT(n_depth, n_color);  // a read a fragment, a write a passing one
  // Non-fast clears write the whole surface: 128 x 128 x 4 bytes, colour once, depth twice.
  color.st.bytes_written += 128 * 128 * 4;
  depth.st.bytes_written += 2 * 128 * 128 * 4;
  expect_same(mem.color.stats(), color.st);
  expect_same(mem.depth.stats(), depth.st);
  // The pipeline's own counts are those of the recorded stream.
  expect_same(stats.memory.rop_color, mem.color.stats());
  expect_same(stats.memory.rop_depth, mem.depth.stats());
}

// The 2D engine is a client of the colour surface (rop_color): render --stats counts its
// pixels' accesses. A 64 x 4 framebuffer, linear, 4 bytes a pixel, 64-byte lines (16
// pixels a line, a row = 4 lines, so row y starts at line 4 y):
// - `rect 0 1 32 1` (PATCOPY: writes only): 32 writes on lines 4 and 5, two misses that
//   read 64 bytes each, 30 hits; the frame-end flush writes the two lines back: read 128,
//   written 128. With DSTINVERT (reads D) each pixel is a read then a write: 64 accesses,
//   the same two misses and bytes. With no cache each access moves its 4 bytes: PATCOPY
//   writes 128; DSTINVERT reads 128 and writes 128.
// - `blit 0 0 0 2 16 1` (SRCCOPY): 16 source reads on line 0, 16 writes on line 8: two
//   misses (read 128), one dirty line flushed (written 64).
MemoryClientStats color_stats_2d(const std::string& draw, const std::vector<std::string>& sets) {
  Config cfg;
  for (const std::string& kv : sets) cfg.apply_override(kv);
  for (const char* kv : {"memory.model=dram", "display.width=64", "display.height=4"}) cfg.apply_override(kv);
  const ArchParams a = ArchParams::resolve(cfg);
  RenderStats stats;
  render_scene(parse_trace("viewport 64 4\n" + draw + "\n", "2d.trace"), a.raster, stats, {},
               Framebuffer::kDefaultTileLog2, 1, a.memory);
  return stats.memory.rop_color;
}

TEST(Memory2d, SpanAndBlitBytesByHand) {
  struct Case {
    std::string draw;
    std::vector<std::string> sets;
    uint64_t accesses, hits, read, written;
  };
  const std::vector<std::string> no_cache = {"rop.color_cache_bytes=0"};
  const Case cases[] = {
      {"rect 0 1 32 1", {}, 32, 30, 128, 128},
      {"rop3 55\nrect 0 1 32 1", {}, 64, 62, 128, 128},
      {"rect 0 1 32 1", no_cache, 32, 0, 0, 128},
      {"rop3 55\nrect 0 1 32 1", no_cache, 64, 0, 128, 128},
      {"rop3 CC\nblit 0 0 0 2 16 1", {}, 32, 30, 128, 64},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.draw + (c.sets.empty() ? "" : ", no cache"));
    const MemoryClientStats s = color_stats_2d(c.draw, c.sets);
    EXPECT_EQ(s.accesses, c.accesses);
    EXPECT_EQ(s.hits, c.hits);
    EXPECT_EQ(s.misses, c.accesses - c.hits);
    EXPECT_EQ(s.bytes_read, c.read);
    EXPECT_EQ(s.bytes_written, c.written);
  }
}

}  // namespace
}  // namespace rastsim
