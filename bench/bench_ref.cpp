// SPDX-License-Identifier: Apache-2.0
// Reference-model throughput: triangles/s and fragments/s through render_scene (setup,
// tiled traversal, interpolation, ROP) and through setup + traversal alone, for
// programmatic scenes on a 1024x768 viewport in s11.8 (max extent 4094 px):
// - SmallTriangles: 10,000 triangles of exactly 4 px^2 (legs 2 x 4 px), seeded random
//   positions and sub-pixel offsets, both windings;
// - LargeTriangles: 4 screen-filling quads (8 triangles) at different depths;
// - MeshGrid: a 64 x 48 grid of quads (6,144 triangles) tiling the viewport.
// The benchmark argument is raster.tile_size. Rates (state.counters, kIsRate) are totals
// over all iterations divided by the thread's CPU time (Google Benchmark's default; the
// model is single-threaded, and CPU time is steadier than wall time on a shared host).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>

#include "ref/pipeline.h"
#include "ref/prim_assembly.h"
#include "ref/tri_setup.h"

namespace rastsim {
namespace {

constexpr int kWidth = 1024, kHeight = 768;
constexpr int kFracBits = 8;

// Exact Q64 for a position in 1/256 px.
Q64 q_at(int64_t sub) { return Q64{i128(sub) << (Q64::kFracBits - kFracBits)}; }

SceneVertex vtx(int64_t sx, int64_t sy, double z, uint8_t r, uint8_t g, uint8_t b) {
  SceneVertex v;
  v.x = q_at(sx);
  v.y = q_at(sy);
  v.z = z;
  v.r = r;
  v.g = g;
  v.b = b;
  return v;
}

Scene make_scene(CmdPrimitives prims) {
  Scene s;
  s.source = "bench";
  s.commands.push_back({CmdViewport{kWidth, kHeight}, {"bench", 1}});
  s.commands.push_back({CmdClear{0, 0, 0}, {"bench", 2}});
  s.commands.push_back({std::move(prims), {"bench", 3}});
  return s;
}

Scene small_triangles() {
  std::mt19937_64 rng(0xbe4c01);
  CmdPrimitives p;
  const int64_t one = int64_t{1} << kFracBits;
  for (int k = 0; k < 10000; ++k) {
    const int64_t x = int64_t(rng() % uint64_t((kWidth - 4) * one)), y = int64_t(rng() % uint64_t((kHeight - 4) * one));
    const uint8_t c = uint8_t(k);
    const double z = double(rng() % 1000) / 1000.0;
    SceneVertex a = vtx(x, y, z, c, 0, 255), b = vtx(x + 2 * one, y, z, 0, c, 0), d = vtx(x, y + 4 * one, z, 255, 0, c);
    if (rng() % 2) std::swap(b, d);
    p.vertices.insert(p.vertices.end(), {a, b, d});
  }
  return make_scene(std::move(p));
}

Scene large_triangles() {
  CmdPrimitives p;
  const int64_t w = int64_t{kWidth} << kFracBits, h = int64_t{kHeight} << kFracBits;
  for (int k = 0; k < 4; ++k) {
    const double z = 0.2 * (k + 1);
    const uint8_t c = uint8_t(60 * k);
    const SceneVertex v00 = vtx(0, 0, z, c, 0, 0), v10 = vtx(w, 0, z, 0, c, 0), v11 = vtx(w, h, z, 0, 0, c),
                      v01 = vtx(0, h, z, c, c, c);
    p.vertices.insert(p.vertices.end(), {v00, v10, v11, v00, v11, v01});
  }
  return make_scene(std::move(p));
}

Scene mesh_grid() {
  std::mt19937_64 rng(0xbe4c02);
  CmdPrimitives p;
  constexpr int nx = 64, ny = 48;
  const int64_t cw = (int64_t{kWidth} << kFracBits) / nx, ch = (int64_t{kHeight} << kFracBits) / ny;
  auto at = [&](int i, int j) {
    return vtx(i * cw, j * ch, double((i + j) % 17) / 16.0, uint8_t(4 * i), uint8_t(5 * j), 128);
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (rng() % 2) p.vertices.insert(p.vertices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      else p.vertices.insert(p.vertices.end(), {at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return make_scene(std::move(p));
}

RasterState bench_state(int tile) {
  RasterState st;
  st.coord_format = FixedFormat{11, kFracBits};
  st.tile_size = tile;
  st.depth_func = DepthFunc::Less;
  st.fb_width = st.viewport_width = kWidth;
  st.fb_height = st.viewport_height = kHeight;
  return st;
}

void set_rates(benchmark::State& state, uint64_t triangles, uint64_t fragments, uint64_t tiles) {
  state.counters["triangles/s"] = benchmark::Counter(double(triangles), benchmark::Counter::kIsRate);
  state.counters["fragments/s"] = benchmark::Counter(double(fragments), benchmark::Counter::kIsRate);
  state.counters["frags/tri"] = benchmark::Counter(triangles ? double(fragments) / double(triangles) : 0.0);
  state.counters["tiles/tri"] = benchmark::Counter(triangles ? double(tiles) / double(triangles) : 0.0);
}

// The whole pipeline: render_scene into a fresh framebuffer each iteration.
void run_pipeline(benchmark::State& state, const Scene& scene) {
  const RasterState st = bench_state(int(state.range(0)));
  uint64_t tris = 0, frags = 0, tiles = 0;
  for (auto _ : state) {
    RenderStats stats;
    Framebuffer fb = render_scene(scene, st, stats);
    benchmark::DoNotOptimize(fb.color_tiles_allocated());
    tris += stats.triangles_in;
    frags += stats.traversal.fragments;
    tiles += stats.traversal.tiles_visited;
  }
  set_rates(state, tris, frags, tiles);
}

// Setup + traversal only (coverage, no interpolation or ROP).
void run_coverage(benchmark::State& state, const Scene& scene) {
  const RasterState st = bench_state(int(state.range(0)));
  const auto& prims = std::get<CmdPrimitives>(scene.commands.back().body);
  const size_t n = triangle_count(prims);
  uint64_t tris = 0, frags = 0, tiles = 0;
  for (auto _ : state) {
    TraversalCounters cnt;
    uint64_t sink = 0;
    for (size_t k = 0; k < n; ++k) {
      SetupTriangle t;
      if (setup_triangle(assemble_triangle(prims, k), st, {"bench", 3}, t) != SetupOutcome::Accepted) continue;
      traverse_triangle(t, st.tile_size, kFracBits, cnt, [&](int px, int py) { sink += unsigned(px ^ py); });
    }
    benchmark::DoNotOptimize(sink);
    tris += n;
    frags += cnt.fragments;
    tiles += cnt.tiles_visited;
  }
  set_rates(state, tris, frags, tiles);
}

void BM_SmallTriangles(benchmark::State& s) { static const Scene sc = small_triangles(); run_pipeline(s, sc); }
void BM_LargeTriangles(benchmark::State& s) { static const Scene sc = large_triangles(); run_pipeline(s, sc); }
void BM_MeshGrid(benchmark::State& s) { static const Scene sc = mesh_grid(); run_pipeline(s, sc); }
void BM_CoverageSmallTriangles(benchmark::State& s) { static const Scene sc = small_triangles(); run_coverage(s, sc); }
void BM_CoverageLargeTriangles(benchmark::State& s) { static const Scene sc = large_triangles(); run_coverage(s, sc); }
void BM_CoverageMeshGrid(benchmark::State& s) { static const Scene sc = mesh_grid(); run_coverage(s, sc); }

void tile_sizes(benchmark::internal::Benchmark* b) {
  b->ArgName("tile");
  for (int t : {2, 4, 8, 16, 32, 64, 128}) b->Arg(t);
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_SmallTriangles)->Apply(tile_sizes);
BENCHMARK(BM_LargeTriangles)->Apply(tile_sizes);
BENCHMARK(BM_MeshGrid)->Apply(tile_sizes);
BENCHMARK(BM_CoverageSmallTriangles)->Apply(tile_sizes);
BENCHMARK(BM_CoverageLargeTriangles)->Apply(tile_sizes);
BENCHMARK(BM_CoverageMeshGrid)->Apply(tile_sizes);

}  // namespace
}  // namespace rastsim
