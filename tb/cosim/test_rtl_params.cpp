// SPDX-License-Identifier: Apache-2.0
// The parameters compiled into the registry of verilated models (model/rtlsim/CMakeLists.txt,
// written by the configure-time exporter) against the shipped configs they were built
// from, read here independently; and the initializer's round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rtlsim/cosim.h"
#include "rtlsim/rtl_params.h"
#include "cosim_test_util.h"

namespace rastsim::rtlsim {
namespace {

TEST(RtlRegistry, CompiledParametersEqualTheShippedConfigs) {
  const auto models = rtl_models();
  ASSERT_FALSE(models.empty());
  for (const RtlModelInfo& m : models) {
    // <cfg>_binned: the shipped config with pipeline.mode = "binned" (rtl/CMakeLists.txt
    // RAST_RTL_BINNED_CONFIGS prepends that line to the config file).
    const bool binned = m.name == m.config + "_binned";
    Config cfg = load_shipped_config(m.config);
    if (binned) {
      cfg.apply_override("pipeline.mode=binned");
      cfg.validate();
    }
    const RtlParams want = rtl_params(ArchParams::resolve(cfg));
    std::string why;
    EXPECT_TRUE(m.params == want) << m.name << ": " << (rtl_params_compatible(m.params, want, &why) ? "" : why);
    EXPECT_TRUE(m.name == m.config || m.name == m.config + "_circuit" || binned) << m.name;
    if (binned) {
      EXPECT_GT(m.params.tile_buffer_samples, 0) << m.name;
    }
  }
  // The default config also with the divider circuit (rtl/CMakeLists.txt RAST_RTL_CIRCUIT_CONFIGS).
  EXPECT_TRUE(std::any_of(models.begin(), models.end(), [](const RtlModelInfo& m) {
    return m.name == "default_circuit" && m.config == "default";
  }));
}

TEST(RtlRegistry, PortWidthsHoldTheSchemaMaxima) {
  // 16384 px displays: pixel coordinates 0..16383 in 14 bits; 128 px tiles: log2 7 in 3 bits.
  const RtlParams p = rtl_params(ArchParams::resolve(load_shipped_config("default")));
  EXPECT_EQ(p.pixel_w, 14);
  EXPECT_EQ(p.tile_log2_w, 3);
  // raster.samples up to 16: the mask of 16 bits, log2 4 in 3 bits; offsets F + 1 = 17 bits (s7.16).
  EXPECT_EQ(p.max_samples, 16);
  EXPECT_EQ(p.sample_log2_w, 3);
  EXPECT_EQ(p.sample_off_w, 17);
}

// raster.max_samples: the build-time MaxSamples, checked against the rules the RTL states
// (rtl/rast_top.sv: a power of two >= 2) and raster.samples <= it.
TEST(RtlParamsMaxSamples, FromConfigAndValidated) {
  Config c = load_shipped_config("embedded");
  c.apply_override("raster.max_samples=4");
  c.apply_override("raster.samples=4");
  c.validate();
  const RtlParams p = rtl_params(ArchParams::resolve(c));
  EXPECT_EQ(p.max_samples, 4);
  EXPECT_EQ(p.sample_log2_w, 3);  // the port keeps the schema's width
  // The run-time sample count up to the built maximum: a 4-sample RTL runs 2, not 8.
  RtlParams two = p, eight = p;
  two.max_samples = 2;
  eight.max_samples = 8;
  std::string why;
  EXPECT_TRUE(rtl_params_compatible(p, two));
  EXPECT_FALSE(rtl_params_compatible(p, eight, &why));
  EXPECT_NE(why.find("MaxSamples (largest raster.samples"), std::string::npos) << why;
  EXPECT_NE(why.find(") is 8, the RTL was built with a maximum of 4"), std::string::npos) << why;

  const auto error_of = [](const std::vector<std::string>& sets) {
    Config bad = load_shipped_config("embedded");
    try {
      for (const auto& s : sets) bad.apply_override(s);
      bad.validate();
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string over = error_of({"raster.max_samples=2", "raster.samples=4"});
  EXPECT_NE(over.find("raster.samples = 4 exceeds raster.max_samples = 2"), std::string::npos) << over;
  EXPECT_NE(error_of({"raster.max_samples=1"}).find("raster.max_samples"), std::string::npos);
  EXPECT_NE(error_of({"raster.max_samples=3"}).find("2, 4, 8 or 16"), std::string::npos) << error_of({"raster.max_samples=3"});
  EXPECT_NE(error_of({"raster.max_samples=32"}).find("raster.max_samples"), std::string::npos);
}

TEST(RtlParamsValues, RoundTripAndWrongCount) {
  const RtlParams p = rtl_params(ArchParams::resolve(load_shipped_config("desktop")));
  std::string text = rtl_params_values(p);  // "{v0, v1, ...}"
  ASSERT_EQ(text.front(), '{');
  ASSERT_EQ(text.back(), '}');
  std::vector<int> values;
  std::istringstream is(text.substr(1, text.size() - 2));
  for (std::string item; std::getline(is, item, ',');) values.push_back(std::stoi(item));
  EXPECT_TRUE(rtl_params_from_values(values) == p);
  EXPECT_THROW(rtl_params_from_values({1, 2, 3}), std::invalid_argument);
}

// The 2D engine's lanes are the schema's largest engine2d.fill_pixels_per_cycle (the
// verilated engine is checked against the table at every run, cosim_driver.h); a
// differing parameter is named.
TEST(Engine2dRtlParams, LanesFromTheSchemaAndMismatchNamed) {
  const Engine2dRtlParams& p = engine2d_rtl_params();
  EXPECT_EQ(p.lanes_max, int(find_param("engine2d.fill_pixels_per_cycle")->max));
  EXPECT_GT(p.width, 0);
  std::string why;
  EXPECT_TRUE(engine2d_rtl_params_compatible(p, p, &why));
  Engine2dRtlParams narrow = p;
  narrow.lanes_max = p.lanes_max / 2;
  EXPECT_FALSE(engine2d_rtl_params_compatible(narrow, p, &why));
  EXPECT_NE(why.find("LanesMax is " + std::to_string(p.lanes_max)), std::string::npos) << why;
}

}  // namespace
}  // namespace rastsim::rtlsim
