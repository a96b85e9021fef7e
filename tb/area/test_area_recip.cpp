// SPDX-License-Identifier: Apache-2.0
// `rastsim area --top rast_recip` builds the reciprocal unit with the config's
// interp.recip_seed_bits and interp.recip_iterations (rtlsim/rtl_params.h root_rtl_params,
// AreaOptions::root_parameters), the settings scripts/recip_precision charts.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common.h"
#include "rtlsim/area.h"
#include "rtlsim/rtl_params.h"
#include "util/process.h"

namespace rastsim {
namespace {

ArchParams arch_with(const std::vector<std::string>& sets) {
  app::ConfigOptions c;
  c.sets = sets;
  return ArchParams::resolve(app::load_config(c));
}

TEST(AreaRecipParams, FromTheConfigForRastRecipOnly) {
  const ArchParams a = arch_with({"interp.recip_seed_bits=4", "interp.recip_iterations=1"});
  using P = std::vector<std::pair<std::string, int>>;
  EXPECT_EQ(root_rtl_params("rast_recip", a), (P{{"SEED_BITS", 4}, {"ITERATIONS", 1}}));
  EXPECT_EQ(root_rtl_params("rast_recip", arch_with({})), (P{{"SEED_BITS", 8}, {"ITERATIONS", 2}}));  // the defaults
  EXPECT_TRUE(root_rtl_params("rast_engine2d", a).empty());
  EXPECT_TRUE(root_rtl_params("rast_top", a).empty());
  EXPECT_EQ(root_rtl_param_names("rast_recip"), (std::vector<std::string>{"SEED_BITS", "ITERATIONS"}));
  AreaOptions o;  // parameters for a module that takes none from the config: an error before Yosys
  o.top = "rast_engine2d";
  o.root_parameters = root_rtl_params("rast_recip", a);
  try {
    synthesize_area(rtl_params(a), o);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("rast_engine2d takes no parameter SEED_BITS"), std::string::npos) << e.what();
  }
}

// One override through the command line, synthesised (a few seconds: two multipliers).
// Its flip-flops counted by hand from rtl/rast_recip.sv as tb/area/test_area.cpp counts
// the default 8 / 2 (355): 3 valid bits (1 + 2 x 1 stages); the seed, b + 2 = 6 bits, and
// d, 40; the one step: its y 6, c 42, the new y 42 (no d after the last step's first
// stage). 139.
TEST(AreaRecip, FourSeedBitsOneStepFromTheCommandLine) {
  try {
    find_yosys();
  } catch (const std::exception&) {
    GTEST_SKIP() << "yosys not installed";
  }
  const std::filesystem::path stats =
      std::filesystem::temp_directory_path() / ("rastsim_area_recip_" + std::to_string(::getpid()) + ".json");
  ProcessOptions po;
  po.out = Sink::Capture;
  po.err = Sink::Stdout;
  const ProcessResult r =
      run_process({RASTSIM_BINARY, "area", "--top", "rast_recip", "--no-cache", "-q", "--set",
                   "interp.recip_seed_bits=4", "--set", "interp.recip_iterations=1", "--stats", stats.string()},
                  po);
  ASSERT_TRUE(WIFEXITED(r.status) && WEXITSTATUS(r.status) == 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
  std::filesystem::remove(stats);
  EXPECT_EQ(j["parameters"]["SEED_BITS"], 4);
  EXPECT_EQ(j["parameters"]["ITERATIONS"], 1);
  EXPECT_EQ(j["flip_flops"], 3 + 6 + 40 + (6 + 42 + 42));
  EXPECT_LT(j["cells"].get<uint64_t>(), 10000u);  // two multipliers, not the default's four (> 10,000)
}

}  // namespace
}  // namespace rastsim
