// SPDX-License-Identifier: Apache-2.0
// The shipped DRAM presets through the config: each resolves and sets every value; the
// peak bandwidths are the data sheets' (worked by hand below); dram.* overrides one value.
#include <gtest/gtest.h>

#include "config/dram_config.h"

namespace rastsim {
namespace {

DramParams resolve(const std::vector<std::string>& sets) {
  Config cfg;
  for (const std::string& s : sets) cfg.apply_override(s);
  return dram_params_from_config(cfg);
}

TEST(DramConfig, EveryPresetResolves) {
  ASSERT_EQ(dram_preset_names(), (std::vector<std::string>{"ddr4_2400", "gddr6", "lpddr4_3200"}));
  for (const std::string& name : dram_preset_names()) {
    SCOPED_TRACE(name);
    const DramParams p = resolve({"memory.preset=" + name});
    EXPECT_EQ(p.check(), "");
    EXPECT_EQ(p.preset, name);
  }
}

// DDR4-2400, 64-bit channel: 2400 MT/s * 8 B = 19.2 GB/s. LPDDR4-3200, two x16
// channels: 2 * 3200 MT/s * 2 B = 12.8 GB/s. GDDR6 14 Gb/s, two x16 channels: 2 * 14e9 *
// 2 B = 56 GB/s.
TEST(DramConfig, PresetPeakBandwidthsAreTheDataSheets) {
  EXPECT_DOUBLE_EQ(resolve({"memory.preset=ddr4_2400"}).peak_bytes_per_second(), 19.2e9);
  EXPECT_DOUBLE_EQ(resolve({"memory.preset=lpddr4_3200"}).peak_bytes_per_second(), 12.8e9);
  EXPECT_DOUBLE_EQ(resolve({"memory.preset=gddr6"}).peak_bytes_per_second(), 56e9);
}

TEST(DramConfig, KeyOverridesOneValue) {
  const DramParams base = resolve({"memory.preset=ddr4_2400"});
  const DramParams p = resolve({"memory.preset=ddr4_2400", "dram.tcl=20", "dram.page_policy=closed",
                                "dram.address_map=ro:ch:ba:bg:co", "clock.core_mhz=600"});
  EXPECT_EQ(base.tCL, 17);
  EXPECT_EQ(p.tCL, 20);
  EXPECT_EQ(p.tRCD, base.tRCD);
  EXPECT_EQ(p.page_policy, PagePolicy::Closed);
  EXPECT_EQ(address_map_name(p.address_map), "ro:ch:ba:bg:co");
  EXPECT_EQ(p.core_khz, 600'000u);
  EXPECT_EQ(p.dram_khz, 1'200'000u);
}

// dram.starvation_cycles is the controller's, no preset's: 0 (off) unless the config sets it.
TEST(DramConfig, StarvationCapIsTheConfigsOwn) {
  for (const char* preset : {"memory.preset=ddr4_2400", "memory.preset=lpddr4_3200", "memory.preset=gddr6"}) {
    EXPECT_EQ(resolve({preset}).starvation_cycles, 0u) << preset;
    EXPECT_EQ(resolve({preset, "dram.starvation_cycles=40"}).starvation_cycles, 40u) << preset;
  }
}

TEST(DramConfig, BadValuesNameTheKey) {
  Config cfg;
  try {
    cfg.apply_override("dram.address_map=ro:ba");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("dram.address_map"), std::string::npos) << e.what();
  }
  try {
    resolve({"dram.burst_length=6"});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("burst length"), std::string::npos) << e.what();
  }
  EXPECT_THROW(cfg.apply_override("memory.preset=ddr5"), ConfigError);
}

}  // namespace
}  // namespace rastsim
