// SPDX-License-Identifier: Apache-2.0
// Co-simulation of multisampling (raster.samples, msaa; docs/rtl.md): the sample count
// and the snapped offsets are run-time inputs of the verilated model, so the shipped
// configs' models run every sample count.
//
// - Random scenes at 1, 2, 4, 8 and 16 samples on the default (s7.16) and d3d11 (s15.8)
//   models, 4 and 8 on embedded (s10.4) and desktop (s12.8), with backpressure: every fragment and its sample mask equal to the reference
//   model's stream, the resolved framebuffer's CRC equal to the reference's.
// - Directed: edges through sample positions (shared edges, both windings), slivers
//   thinner than a pixel, triangles whose pixels have samples but no centre (the clamp).
// - Timing, against the equations of config/timing_params.h on a serial path (one
//   triangle in one tile): going from 1 to S samples adds exactly the fine raster's
//   ceil(A S / samples_per_cycle) - ceil(A / samples_per_cycle), the interpolator's and
//   the ROP's extra work (rop_accesses) and the resolve pass.
// - raster.aa_mode = ssaa: an error naming the key.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "config/raster_state_config.h"
#include "config/timing_params.h"
#include "cosim_test_util.h"
#include "ref/coarse_raster.h"
#include "ref/prim_assembly.h"
#include "ref/tri_setup.h"
#include "rtlsim/cosim.h"

namespace rastsim::rtlsim {
namespace {

// memory.model = fixed: these tests check masks, fragments, resolved CRCs and the fixed
// cost's equations (cosim_test_util.h, load_shipped_config_fixed_memory; the ctest
// cosim.msaa.* tests co-simulate multisampling with the configs' dram).
Config with_samples(const char* config, int samples) {
  Config cfg = load_shipped_config_fixed_memory(config);
  cfg.apply_override("raster.samples=" + std::to_string(samples));
  cfg.validate();
  return cfg;
}

struct MsaaCase {
  const char* config;
  int samples;
  int tile;
};
class MsaaRandomCosim : public ::testing::TestWithParam<MsaaCase> {};

TEST_P(MsaaRandomCosim, FragmentsMasksAndResolvedCrc) {
  Config cfg = with_samples(GetParam().config, GetParam().samples);
  cfg.apply_override("raster.out_of_range=cull");
  const uint64_t seed = 0xaa000000u + uint64_t(GetParam().samples) * 64 + uint64_t(GetParam().tile);
  const CosimResult r = run_random_scene(cfg, seed, 1000, GetParam().tile);
  std::cout << r.fragments_compared << " fragments, " << r.rop_accesses << " ROP accesses, " << r.cycles_rtl
            << " cycles (resolve " << r.resolve_cycles << "), " << r.wall_seconds << " s\n";
  expect_clean(r);
  EXPECT_EQ(r.samples, GetParam().samples);
  EXPECT_EQ(r.crc_rtl, r.crc_ref);
  EXPECT_GT(r.fragments_compared, 5000u);
  // Partially covered pixels cost one access per covered sample: from 4 samples on some
  // partial pixels have several, so the ROP does more accesses than fragments (with 2, a
  // partial pixel has one sample: one access, as a full one).
  if (GetParam().samples > 2) EXPECT_GT(r.rop_accesses, r.fragments_compared);
  else EXPECT_EQ(r.rop_accesses, r.fragments_compared);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, MsaaRandomCosim,
    ::testing::Values(MsaaCase{"default", 1, 16}, MsaaCase{"default", 2, 8}, MsaaCase{"default", 4, 16},
                      MsaaCase{"default", 4, 4}, MsaaCase{"default", 8, 16}, MsaaCase{"default", 16, 8},
                      MsaaCase{"d3d11", 4, 16}, MsaaCase{"d3d11", 8, 8}, MsaaCase{"d3d11", 16, 16},
                      // s10.4: offsets exactly the 1/16 px table (F = 4); 4 sample lanes.
                      MsaaCase{"embedded", 4, 8}, MsaaCase{"embedded", 8, 8},
                      // 16 sample lanes, 4 tiles a cycle in the coarse raster.
                      MsaaCase{"desktop", 4, 16}, MsaaCase{"desktop", 16, 16}),
    [](const auto& info) {
      return std::string(info.param.config) + "Samples" + std::to_string(info.param.samples) + "Tile" +
             std::to_string(info.param.tile);
    });

// Edges through sample positions and pixel centres, shared edges of both windings,
// slivers narrower than a pixel (pixels with samples but no covered centre: the
// extrapolated, clamped attributes), a triangle covering the viewport.
Scene msaa_directed_scene(const Config& cfg) {
  const int w = static_cast<int>(cfg.get_int("display.width")), h = static_cast<int>(cfg.get_int("display.height"));
  DirectedScene d("msaa", 17);
  auto add = [&](double x0, double y0, double x1, double y1, double x2, double y2) { d.add(x0, y0, x1, y1, x2, y2); };
  // A quad split along its diagonal, both windings; edges on 1/16 px sample offsets.
  add(8.125, 8.375, 40.625, 8.375, 8.125, 40.875);
  add(40.625, 8.375, 40.625, 40.875, 8.125, 40.875);
  add(60.5, 8.5, 60.5, 40.5, 90.5, 8.5);
  add(90.5, 8.5, 60.5, 40.5, 90.5, 40.5);
  // Slivers: thinner than the sample spacing, horizontal, vertical and diagonal.
  add(2, 50.3, w - 2, 50.4, w - 2, 50.55);
  add(100.3, 2, 100.45, h - 2, 100.5, h - 2);
  add(3.1, 3.2, w - 3.3, h - 4.1, w - 3.1, h - 3.7);
  add(20.02, 70.01, 20.3, 70.2, 20.1, 70.4);  // smaller than a pixel
  // Covering the viewport (accepted tiles: full masks) and crossing its border.
  add(-8, -8, w + 8, -8, -8, h + 8);
  add(w + 8, -8, w + 8, h + 8, -8, h + 8);
  add(-5.3, h / 2.0, w / 2.0, -4.7, w + 3.1, h + 2.9);
  return d.scene;
}

TEST(MsaaDirectedCosim, EdgeCasesAtEverySampleCount) {
  for (const char* config : {"default", "d3d11"})
    for (int samples : {2, 4, 8, 16}) {
      SCOPED_TRACE(std::string(config) + " samples " + std::to_string(samples));
      const Config cfg = with_samples(config, samples);
      CosimOptions o;
      o.tile_size = 8;
      o.backpressure = 0.5;
      o.stress_seed = 3;
      const CosimResult r = run_cosim(msaa_directed_scene(cfg), ArchParams::resolve(cfg), o);
      expect_clean(r);
      EXPECT_EQ(r.crc_rtl, r.crc_ref);
    }
}

// One triangle inside one partial tile: the RTL's path is serial (setup, coarse, fine,
// interpolation, ROP, resolve), so the cycles added by S samples are the equations'.
TEST(MsaaTiming, OneTileAddsTheEquationsCycles) {
  for (const char* config : {"default", "d3d11"}) {
    DirectedScene d("timing", 5);
    d.add(3.3, 2.7, 12.6, 4.1, 6.2, 13.4);
    const Scene& scene = d.scene;
    struct Work {
      uint64_t cycles_rtl, fine, interp, rop, resolve;
    };
    auto work = [&](int samples) {
      const Config cfg = with_samples(config, samples);  // fixed: the equations are the ROP's fixed cost
      const RasterState st = raster_state_from_config(cfg);
      const TimingParams tp = TimingParams::from_config(cfg);
      const auto* prims = std::get_if<CmdPrimitives>(&scene.commands[0].body);
      SetupTriangle t;
      EXPECT_EQ(setup_triangle(assemble_triangle(*prims, 0), st, scene.commands[0].loc, t), SetupOutcome::Accepted);
      TraversalCounters c;
      uint64_t accesses = 0;
      traverse_triangle(t, st.tile_size, st.coord_format.frac_bits, c,
                        [&](int, int, uint32_t m) { accesses += TimingParams::rop_accesses(m, samples); });
      EXPECT_EQ(c.tiles_partial, 1u);
      EXPECT_EQ(c.tiles_accepted, 0u);
      const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg));
      expect_clean(r);
      EXPECT_EQ(r.rop_accesses, accesses);
      const uint64_t fb = uint64_t(st.fb_width) * uint64_t(st.fb_height);
      return Work{r.cycles_rtl, tp.fine_partial_cycles(c.pixel_tests, samples), tp.interp_batch_cycles(c.fragments),
                  tp.rop_fragment_cycles(accesses), tp.resolve_cycles(fb, samples)};
    };
    const Work one = work(1);
    EXPECT_EQ(one.resolve, 0u);
    for (int samples : {2, 4, 8, 16}) {
      const Work s = work(samples);
      const uint64_t added = (s.fine - one.fine) + (s.interp - one.interp) + (s.rop - one.rop) + s.resolve;
      std::cout << config << " samples " << samples << ": RTL " << s.cycles_rtl << " cycles, 1 sample " << one.cycles_rtl
                << ", equations add " << added << " (fine " << one.fine << " -> " << s.fine << ", resolve "
                << s.resolve << ")\n";
      EXPECT_EQ(s.cycles_rtl - one.cycles_rtl, added) << config << " samples " << samples;
    }
  }
}

TEST(MsaaCosim, SsaaHasNoRtlAndSaysWhichKey) {
  Config cfg = with_samples("default", 4);
  cfg.apply_override("raster.aa_mode=ssaa");
  cfg.validate();
  Scene scene;
  scene.source = "ssaa";
  try {
    run_cosim(scene, ArchParams::resolve(cfg));
    FAIL() << "ssaa co-simulated";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("raster.aa_mode"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rastsim::rtlsim
