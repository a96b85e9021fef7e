// SPDX-License-Identifier: Apache-2.0
// raster.max_samples (the RTL's MaxSamples, a build-time parameter): the embedded config
// with raster.max_samples = 2 is built on demand into a cache in the build tree (one
// Verilator build, about a minute: ctest label rtlbuild) and co-simulated on a shipped
// scene at 1 and 2 samples. Independent check: the shipped embedded model (MaxSamples =
// 16, prebuilt) on the same scene and sample count: 0 mismatches on both, the same
// fragments, the same RTL cycle count and framebuffer CRC. The sample mask bits beyond the
// count are never set, so the narrower FIFOs must not change a cycle.
#include <gtest/gtest.h>

#include <string>

#include "cosim_test_util.h"
#include "rtlsim/cosim.h"
#include "rtlsim/cosim_setup.h"
#include "rtlsim/rtl_cache.h"
#include "rtlsim/rtl_params.h"
#include "scene/scene_io.h"

namespace rastsim::rtlsim {
namespace {

Config embedded_with(int samples, int max_samples) {
  Config c = load_shipped_config("embedded");
  c.apply_override("raster.samples=" + std::to_string(samples));
  if (max_samples) c.apply_override("raster.max_samples=" + std::to_string(max_samples));
  c.validate();
  return c;
}

TEST(RtlMaxSamples, SmallModelMatchesShippedModel) {
  const std::string path = std::string(RASTSIM_SOURCE_DIR) + "/traces/primitives.trace";
  const Scene scene = load_trace(path);
  for (int samples : {1, 2}) {
    SCOPED_TRACE("raster.samples = " + std::to_string(samples));
    // The shipped model (MaxSamples = 16) with the config as shipped.
    const Config shipped_cfg = embedded_with(samples, 0);
    ASSERT_EQ(rtl_params(ArchParams::resolve(shipped_cfg)).max_samples, 16);
    const CosimResult want = run_cosim(scene, ArchParams::resolve(shipped_cfg), {});
    ASSERT_EQ(want.rtl_config, "embedded");

    // The same config built with MaxSamples = 2, through the RTL cache.
    const Config small_cfg = embedded_with(samples, 2);
    const RtlParams build = rtl_params(ArchParams::resolve(small_cfg));
    ASSERT_EQ(build.max_samples, 2);
    RtlBuildOptions bo;
    bo.cache_dir = RASTSIM_TEST_CACHE;
    bo.label = "embedded --set raster.max_samples=2";
    const RtlCacheEntry e = find_or_build_rtl_model(build, build, bo);
    ASSERT_EQ(e.params.max_samples, 2) << e.dir;
    CosimResult got = run_rtl_runner(e, runner_request(scene, ArchParams::resolve(small_cfg), {})).get<CosimResult>();

    EXPECT_EQ(want.mismatches, 0u) << want.first_mismatch;
    EXPECT_EQ(got.mismatches, 0u) << got.first_mismatch;
    EXPECT_GT(got.fragments_compared, 0u);
    EXPECT_EQ(got.fragments_compared, want.fragments_compared);
    EXPECT_EQ(got.cycles_rtl, want.cycles_rtl);
    EXPECT_EQ(got.crc_rtl, want.crc_rtl);
    EXPECT_EQ(got.crc_rtl, got.crc_ref);
  }
}

}  // namespace
}  // namespace rastsim::rtlsim
