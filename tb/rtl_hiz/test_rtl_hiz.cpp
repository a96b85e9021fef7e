// SPDX-License-Identifier: Apache-2.0
// Hierarchical Z's RTL, the bound table (rtl/rast_hiz.sv) and the tile test
// (rtl/rast_hiz_test.sv), against the reference's HizTable and tile_depth_range
// (model/ref/hiz.h, the one source of the decisions) at each verilated set (hiz_sets.h).
//
// A run is many random scenes on a 48 x 40 screen (partial edge blocks at every block
// size), each from reset: random triangles (half the scenes sorted front to back, so
// tiles are culled; a quarter of the triangles large, a quarter flat, ten drawn twice so
// that ranges equal bounds, where less and lequal differ), a depth function the mode
// handles, depth writes on or (a quarter of the scenes) off, a random depth clear half
// way. The walk is the reference's (tile_range, classify_tile); for every tile coarse
// raster keeps, the table's bounds over the footprint and the test's decision are read
// from the RTL and checked against HizTable::bounds and HizTable::test; a drawn tile's
// depth writes (the reference's: each covered pixel's plane depth, depth-tested against
// a depth buffer, Hi-Z accepted tiles with `always`) go to both tables, the RTL's 1 ..
// Lanes a cycle. At the scene's end the layer completions and every block's bounds are
// compared. Independently of the reference, every culled (accepted) tile is checked by
// brute force: each covered pixel's depth fails (passes) the test against the buffer.
// The seed is printed; RASTSIM_HIZ_SEED=<n> replays a run, =random draws a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/rtl_unit_test.h"
#include "common/screen_vertex.h"
#include "config/config.h"
#include "config/raster_state_config.h"
#include "hiz_sets.h"
#include "ref/coarse_raster.h"
#include "ref/fine_raster.h"
#include "ref/framebuffer.h"
#include "ref/hiz.h"
#include "ref/interpolate.h"
#include "ref/rop.h"
#include "ref/tri_setup.h"
#include "rtlsim/port_bits.h"

namespace {

using namespace rastsim;
using rtlsim::port_bits;
using rtlsim::set_port_bits;

constexpr int kWidth = 48, kHeight = 40;

uint64_t seed() {
  static const uint64_t s = test::seed_from_env("RASTSIM_HIZ_SEED", 29);
  return s;
}

struct HizSet {
  const char* name;
  const char* config;
  int depth_w, pixel_w, block_log2, minmax, blocks, tile_log2_max, lanes;
};

// The widths of a config's tile test (its rast_params.vh).
struct TestWidths {
  int coef_w, edge_w, area_w;
};

struct Totals {
  uint64_t tested = 0, culled = 0, accepted = 0, writes = 0, completions = 0, brute_checked = 0;
};

template <class T>
void clock(T& m) {
  m.clk_i = 0, m.eval();
  m.clk_i = 1, m.eval();
}

// One set: the tile test model TestM, the table model TableM.
template <class TestM, class TableM>
class HizBench {
 public:
  HizBench(const HizSet& s, std::mt19937_64& rng) : s_(s), rng_(rng) {
    Config cfg;
    cfg.load_file(std::string(RASTSIM_SOURCE_DIR) + "/configs/" + s.config + ".toml");
    cfg.apply_override("display.width=" + std::to_string(kWidth));
    cfg.apply_override("display.height=" + std::to_string(kHeight));
    cfg.validate();
    base_ = raster_state_from_config(cfg);
    w_ = TestWidths{base_.coord_format.int_bits + base_.coord_format.frac_bits + 2,
                    2 * (base_.coord_format.int_bits + base_.coord_format.frac_bits) + 3,
                    2 * (base_.coord_format.int_bits + base_.coord_format.frac_bits) + 2};
  }

  void scene(int index, Totals& tot);

 private:
  void reset();
  std::vector<std::array<SceneVertex, 3>> triangles(bool front_to_back);
  void tile(const SetupTriangle& t, const PixelRect& fp, TileClass cls, Totals& tot);
  void bounds(const PixelRect& fp, uint32_t& lo, uint32_t& hi);
  void write(const std::vector<std::array<uint32_t, 3>>& w, Totals& tot);
  void clear(uint32_t z);

  HizSet s_;
  std::mt19937_64& rng_;
  RasterState base_, st_;
  TestWidths w_{};
  TestM test_;
  TableM table_;
  std::optional<HizTable> ref_;
  Framebuffer fb_{kWidth, kHeight, 1};
  uint64_t completions_ = 0;
};

template <class TestM, class TableM>
void HizBench<TestM, TableM>::reset() {
  table_.rst_ni = 1, table_.clk_i = 0, table_.clear_i = 0, table_.wr_valid_i = 0;
  table_.fb_width_i = kWidth, table_.fb_height_i = kHeight;
  table_.eval();
  table_.rst_ni = 0, table_.eval();
  table_.rst_ni = 1, table_.eval();
}

// Random triangles over the screen (a margin outside it): depth in [0, 1] around a
// level a triangle, a quarter of them large; sorted by nearest vertex depth when asked.
template <class TestM, class TableM>
std::vector<std::array<SceneVertex, 3>> HizBench<TestM, TableM>::triangles(bool front_to_back) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::pair<double, std::array<SceneVertex, 3>>> tris;
  for (int k = 0; k < 40; ++k) {
    const bool large = rng_() % 4 == 0;
    const double cx = -4 + u(rng_) * (kWidth + 8), cy = -4 + u(rng_) * (kHeight + 8);
    const double r = large ? 30 + u(rng_) * 20 : 2 + u(rng_) * 14;
    const double level = 0.05 + 0.9 * u(rng_), slope = rng_() % 4 == 0 ? 0.0 : 0.1 * u(rng_);  // some flat
    std::array<SceneVertex, 3> v;
    double nearest = 1;
    for (int i = 0; i < 3; ++i) {
      const double z = std::clamp(level + slope * (u(rng_) - 0.5), 0.0, 1.0);
      nearest = std::min(nearest, z);
      v[size_t(i)] = screen_vertex(std::clamp(cx + (u(rng_) - 0.5) * 2 * r, -8.0, kWidth + 8.0),
                                   std::clamp(cy + (u(rng_) - 0.5) * 2 * r, -8.0, kHeight + 8.0), z, 200);
    }
    tris.push_back({nearest, v});
  }
  if (front_to_back)
    std::stable_sort(tris.begin(), tris.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::array<SceneVertex, 3>> out;
  for (auto& t : tris) out.push_back(t.second);
  // Ten drawn again: a tile's range equal to a bound (less and lequal part there).
  for (size_t k = 0; k < 10; ++k) out.push_back(tris[k].second);
  return out;
}

// The RTL table's bounds over footprint fp.
template <class TestM, class TableM>
void HizBench<TestM, TableM>::bounds(const PixelRect& fp, uint32_t& lo, uint32_t& hi) {
  const int P = s_.pixel_w;
  table_.q_fp_i = 0;
  set_port_bits(table_.q_fp_i, 0, P, uint64_t(fp.x0));
  set_port_bits(table_.q_fp_i, P, P, uint64_t(fp.y0));
  set_port_bits(table_.q_fp_i, 2 * P, P, uint64_t(fp.x1));
  set_port_bits(table_.q_fp_i, 3 * P, P, uint64_t(fp.y1));
  table_.eval();
  lo = uint32_t(table_.q_min_o);
  hi = uint32_t(table_.q_max_o);
}

// Depth writes {x, y, z} in order, 1 .. Lanes a cycle.
template <class TestM, class TableM>
void HizBench<TestM, TableM>::write(const std::vector<std::array<uint32_t, 3>>& w, Totals& tot) {
  const int P = s_.pixel_w, D = s_.depth_w;
  for (size_t i = 0; i < w.size();) {
    const size_t n = std::min(w.size() - i, size_t(1 + rng_() % uint64_t(s_.lanes)));
    table_.wr_valid_i = 0;
    for (size_t j = 0; j < n; ++j) {
      set_port_bits(table_.wr_valid_i, int(j), 1, 1);
      set_port_bits(table_.wr_x_i, int(j) * P, P, w[i + j][0]);
      set_port_bits(table_.wr_y_i, int(j) * P, P, w[i + j][1]);
      set_port_bits(table_.wr_z_i, int(j) * D, D, w[i + j][2]);
    }
    table_.clk_i = 0, table_.eval();
    completions_ += uint64_t(table_.completions_o);
    table_.clk_i = 1, table_.eval();
    i += n;
    tot.writes += n;
  }
  table_.wr_valid_i = 0;
  table_.eval();
}

template <class TestM, class TableM>
void HizBench<TestM, TableM>::clear(uint32_t z) {
  ref_->clear(z);
  fb_.clear_depth(z);
  table_.clear_i = 1;
  table_.clear_z_i = z;
  clock(table_);
  table_.clear_i = 0;
  table_.eval();
}

// One tile coarse raster keeps: the bounds and the decision against the reference's,
// the decision by brute force, then a drawn tile's writes.
template <class TestM, class TableM>
void HizBench<TestM, TableM>::tile(const SetupTriangle& t, const PixelRect& fp, TileClass cls, Totals& tot) {
  const int F = st_.coord_format.frac_bits, D = s_.depth_w, P = s_.pixel_w;
  uint32_t lo = 0, hi = 0;
  bounds(fp, lo, hi);
  const DepthRange rb = ref_->bounds(fp);
  ASSERT_EQ(hi, uint64_t(rb.hi)) << "bound max, footprint " << fp.x0 << "," << fp.y0;
  if (s_.minmax) ASSERT_EQ(lo, uint64_t(rb.lo)) << "bound min, footprint " << fp.x0 << "," << fp.y0;
  test_.minmax_i = s_.minmax;
  test_.depth_func_i = uint8_t(st_.depth_func);
  for (int e = 0; e < 3; ++e) {
    set_port_bits(test_.a_i, e * w_.coef_w, w_.coef_w, uint64_t(t.edge[size_t(e)].a));
    set_port_bits(test_.b_i, e * w_.coef_w, w_.coef_w, uint64_t(t.edge[size_t(e)].b));
    set_port_bits(test_.c_i, e * w_.edge_w, w_.edge_w, uint64_t(t.edge[size_t(e)].c));
    set_port_bits(test_.z_i, e * D, D, t.z[size_t(e)]);
  }
  set_port_bits(test_.area2_i, 0, w_.area_w, uint64_t(t.area2));
  test_.origin_i = 0;
  set_port_bits(test_.origin_i, 0, P, uint64_t(t.origin_x));
  set_port_bits(test_.origin_i, P, P, uint64_t(t.origin_y));
  test_.fp_i = 0;
  set_port_bits(test_.fp_i, 0, P, uint64_t(fp.x0));
  set_port_bits(test_.fp_i, P, P, uint64_t(fp.y0));
  set_port_bits(test_.fp_i, 2 * P, P, uint64_t(fp.x1));
  set_port_bits(test_.fp_i, 3 * P, P, uint64_t(fp.y1));
  test_.bound_min_i = s_.minmax ? lo : 0;
  test_.bound_max_i = hi;
  test_.eval();
  const HizDecision d = ref_->test(fp, tile_depth_range(t, fp, F), st_.depth_func);
  ASSERT_TRUE(test_.handled_o);
  ++tot.tested;
  const HizDecision rtl = test_.cull_o ? HizDecision::Culled : test_.accept_o ? HizDecision::Accepted : HizDecision::Draw;
  ASSERT_EQ(int(rtl), int(d)) << "decision, footprint " << fp.x0 << "," << fp.y0 << " - " << fp.x1 << "," << fp.y1;
  // The brute force: every covered pixel against the buffer as the ROP would test it.
  const DepthFunc func = d == HizDecision::Accepted ? DepthFunc::Always : st_.depth_func;
  std::vector<std::array<uint32_t, 3>> writes;
  const auto pixel = [&](int px, int py, uint32_t) {
    const uint32_t z = interpolate_plane(t, px, py, F).z;
    const bool pass = depth_test(st_.depth_func, z, fb_.depth_at(px, py, 0));
    if (d == HizDecision::Culled) EXPECT_FALSE(pass) << "culled tile, pixel " << px << "," << py;
    if (d == HizDecision::Accepted) EXPECT_TRUE(pass) << "accepted tile, pixel " << px << "," << py;
    ++tot.brute_checked;
    if (d == HizDecision::Culled || !depth_test(func, z, fb_.depth_at(px, py, 0)) || !st_.depth_write) return;
    writes.push_back({uint32_t(px), uint32_t(py), z});
  };
  if (cls == TileClass::Accepted) fine_raster_accepted(fp, pixel);
  else fine_raster_partial(t, fp, F, pixel);
  if (d == HizDecision::Culled) {
    ++tot.culled;
    return;
  }
  if (d == HizDecision::Accepted) ++tot.accepted;
  for (const auto& w : writes) {
    fb_.set_depth(int(w[0]), int(w[1]), 0, w[2]);
    ref_->write(int(w[0]), int(w[1]), w[2]);
  }
  ref_->flush();
  write(writes, tot);
}

template <class TestM, class TableM>
void HizBench<TestM, TableM>::scene(int index, Totals& tot) {
  st_ = base_;
  st_.tile_size = 1 << (s_.tile_log2_max - int(rng_() % 2));
  const std::vector<DepthFunc> funcs = s_.minmax
      ? std::vector<DepthFunc>{DepthFunc::Less, DepthFunc::LEqual, DepthFunc::Greater, DepthFunc::GEqual}
      : std::vector<DepthFunc>{DepthFunc::Less, DepthFunc::LEqual};
  st_.depth_func = funcs[rng_() % funcs.size()];
  st_.depth_write = rng_() % 4 != 0;
  const bool far_first = st_.depth_func == DepthFunc::Greater || st_.depth_func == DepthFunc::GEqual;
  SCOPED_TRACE(std::string(s_.name) + " scene " + std::to_string(index) + " func " + to_string(st_.depth_func) +
               " tile " + std::to_string(st_.tile_size));
  const uint32_t far = uint32_t((uint64_t{1} << s_.depth_w) - 1);
  ref_.emplace(s_.minmax ? HizMode::MinMax : HizMode::Max, 1 << s_.block_log2, int64_t{1} << 30, kWidth, kHeight,
               s_.depth_w);
  ASSERT_EQ(ref_->blocks(), s_.blocks);
  fb_.clear_depth(far);
  completions_ = 0;
  reset();
  ASSERT_FALSE(table_.overflow_o);
  if (far_first) clear(0);
  std::vector<std::array<SceneVertex, 3>> tris = triangles(index % 2 == 0);
  if (far_first) std::reverse(tris.begin(), tris.end());
  for (size_t k = 0; k < tris.size(); ++k) {
    if (k == tris.size() / 2 && rng_() % 2) clear(uint32_t(rng_() % (uint64_t(far) + 1)));
    SetupTriangle t;
    if (setup_triangle(tris[k], st_, {"hiz", int(k)}, t) != SetupOutcome::Accepted) continue;
    const int F = st_.coord_format.frac_bits;
    const PixelRect tiles = tile_range(t.bbox, st_.tile_size);
    for (int ty = tiles.y0; ty < tiles.y1; ++ty)
      for (int tx = tiles.x0; tx < tiles.x1; ++tx) {
        const PixelRect fp = tile_footprint(t.bbox, st_.tile_size, tx, ty);
        const TileClass cls = classify_tile(t, fp, F);
        if (cls == TileClass::Rejected) continue;
        tile(t, fp, cls, tot);
        if (testing::Test::HasFatalFailure()) return;
      }
  }
  EXPECT_EQ(completions_, ref_->stats.layer_completions);
  tot.completions += completions_;
  const int B = 1 << s_.block_log2;
  for (int by = 0; by * B < kHeight; ++by)
    for (int bx = 0; bx * B < kWidth; ++bx) {
      const PixelRect blk{bx * B, by * B, std::min(kWidth, (bx + 1) * B), std::min(kHeight, (by + 1) * B)};
      uint32_t lo = 0, hi = 0;
      bounds(blk, lo, hi);
      EXPECT_EQ(hi, uint64_t(ref_->bounds(blk).hi)) << "block " << bx << "," << by;
      if (s_.minmax) EXPECT_EQ(lo, uint64_t(ref_->bounds(blk).lo)) << "block " << bx << "," << by;
    }
}

template <class TestM, class TableM>
void run_set(const HizSet& s) {
  std::mt19937_64 rng(seed() ^ std::hash<std::string>{}(s.name));
  HizBench<TestM, TableM> bench(s, rng);
  Totals tot;
  for (int i = 0; i < 200 && !testing::Test::HasFatalFailure(); ++i) bench.scene(i, tot);
  std::printf("%s: %llu tiles tested, %llu culled, %llu accepted, %llu depth writes, %llu layer completions, "
              "%llu pixels checked by brute force\n",
              s.name, (unsigned long long)tot.tested, (unsigned long long)tot.culled,
              (unsigned long long)tot.accepted, (unsigned long long)tot.writes, (unsigned long long)tot.completions,
              (unsigned long long)tot.brute_checked);
  // The scenes exercise every decision and the layer rule.
  EXPECT_GT(tot.culled, 50u);
  if (s.minmax) EXPECT_GT(tot.accepted, 20u);
  EXPECT_GT(tot.completions, 10u);
}

#define RAST_HIZ_TEST(name, config, depth_w, pixel_w, block_log2, minmax, blocks, tile_log2_max, lanes)          \
  TEST(RtlHiz, name) {                                                                                            \
    run_set<Vrast_hiz_test_##config, Vrast_hiz_##name>(                                                           \
        HizSet{#name, #config, depth_w, pixel_w, block_log2, minmax, blocks, tile_log2_max, lanes});               \
  }
RAST_HIZ_SETS(RAST_HIZ_TEST)

}  // namespace
