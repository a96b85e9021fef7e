// SPDX-License-Identifier: Apache-2.0
// Mipmaps, trilinear and the level of detail in rast_top's texture stage (docs/texture.md
// "RTL"; ctest names cosim.texture.mip.*, labels cosim and texture): the notes' textured
// box (tb/data/boxT.obj, perspective-correct, its 8 x 8 checker: levels 8x8 .. 1x1)
// drawn with `mipmap on` and each filter, and with a lod bias, co-simulated fragment by
// fragment against the reference (every fragment after texenv, the helper pixels' count,
// the image: the reference's CRC), and the SystemC model's image the RTL's and its cycles
// within 2 % of them (memory.model = fixed). The textured traces and a random scene are
// the command-line tests cosim.texture.default.*mip* (tb/cosim/CMakeLists.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "scene/scene_io.h"

#include "config/obj_placement.h"
#include "cosim_test_util.h"
#include "fidelity/run_child.h"
#include "sc/raster_pipeline.h"

namespace rastsim::rtlsim {
namespace {

const std::string kData = RASTSIM_SOURCE_DIR "/tb/data";

// An OBJ scene with every textured command drawn with `filter`, mipmap on and `bias` (s.8).
Scene mip_obj(const std::string& path, const Config& cfg, TexFilter filter, int32_t bias) {
  Scene scene = load_obj(path, obj_placement_from_config(cfg));
  int textured = 0;
  for (Command& c : scene.commands)
    if (auto* p = std::get_if<CmdPrimitives>(&c.body); p && p->texture.enabled()) {
      p->texture.filter = filter;
      p->texture.mipmap = true;
      p->texture.lod_bias = bias;
      ++textured;
    }
  EXPECT_GT(textured, 0) << path << " binds a texture";
  return scene;
}
Scene mip_box(const Config& cfg, TexFilter filter, int32_t bias) { return mip_obj(kData + "/boxT.obj", cfg, filter, bias); }

// The RTL against the reference (clean, the reference's CRC) and the SystemC model (its
// CRC, cycles within 2 %), with the figures printed for docs/texture.md's table.
void expect_mip_cosim(const Scene& scene, const Config& cfg, const char* what) {
  const CosimResult r = run_cosim(scene, ArchParams::resolve(cfg));
  expect_clean(r);
  EXPECT_EQ(r.crc_rtl, r.crc_ref);
  EXPECT_GT(r.helper_pixels, 0u);
  const nlohmann::json m = fidelity::run_in_child([&] {
    const sc::SimResult s = sc::simulate_scene(scene, ArchParams::resolve(cfg));
    return nlohmann::json{{"cycles", s.cycles}, {"crc", s.render.framebuffer_crc32},
                          {"trilinear", s.render.texture.samples[size_t(TexFilter::Trilinear)]}};
  });
  const auto cycles_model = m.at("cycles").get<uint64_t>();
  EXPECT_EQ(m.at("crc").get<uint32_t>(), r.crc_rtl);
  const double error = (double(cycles_model) - double(r.cycles_rtl)) / double(r.cycles_rtl);
  std::cout << what << ": fragments " << r.fragments_compared << ", helper pixels " << r.helper_pixels
            << ", texel fetches " << r.texel_fetches << ", RTL " << r.cycles_rtl << ", SystemC " << cycles_model
            << ", error " << 100.0 * error << " %\n";
  EXPECT_LE(std::abs(error), 0.02);
}

// The box with a filter and a bias (s.8). Its faces magnify the 8 x 8 texture about 2.5 to
// 8 times (lambda -1.3 to -3): without a bias level 0 only (trilinear's weight 0: one
// level read, one slot); a bias of +2.5 to +4 moves them onto levels 1 to 3, and
// trilinear between them.
struct BoxCase {
  const char* name;
  TexFilter filter;
  int32_t bias;
};
void PrintTo(const BoxCase& c, std::ostream* os) { *os << c.name; }  // the ctest name's parameter
class Box : public ::testing::TestWithParam<BoxCase> {};

TEST_P(Box, MipmappedMatchesTheReferenceAndSystemC) {
  const Config cfg = load_shipped_config_fixed_memory("default");
  const BoxCase& c = GetParam();
  expect_mip_cosim(mip_box(cfg, c.filter, c.bias), cfg, c.name);
}

INSTANTIATE_TEST_SUITE_P(Filters, Box,
                         ::testing::Values(BoxCase{"Trilinear", TexFilter::Trilinear, 0},
                                           BoxCase{"BilinearBias2_5", TexFilter::Bilinear, 640},
                                           BoxCase{"NearestBias4", TexFilter::Nearest, 1024},
                                           BoxCase{"TrilinearBias3_25", TexFilter::Trilinear, 832}),
                         [](const ::testing::TestParamInfo<BoxCase>& i) { return std::string(i.param.name); });

// glmark2's crate (scripts/workloads writes out/workloads/crate.obj, its placement
// crate.set and its 512 x 512 texture: levels 512 .. 1) on configs/d3d11.toml, trilinear
// mipmapped: minified, so most fragments blend two levels.
TEST(Crate, TrilinearMipmapped) {
  const std::string dir = RASTSIM_SOURCE_DIR "/out/workloads";
  std::ifstream set(dir + "/crate.set");
  if (!std::filesystem::exists(dir + "/crate.obj") || !set)
    GTEST_SKIP() << "no " << dir << "/crate.obj: scripts/workloads --no-render writes it (glmark2-data, assimp)";
  Config cfg = load_shipped_config_fixed_memory("d3d11");
  for (std::string line; std::getline(set, line);)
    if (!line.empty()) cfg.apply_override(line);
  cfg.apply_override("raster.depth_func=less");
  cfg.validate();
  expect_mip_cosim(mip_obj(dir + "/crate.obj", cfg, TexFilter::Trilinear, 0), cfg, "crate trilinear, d3d11");
}

}  // namespace
}  // namespace rastsim::rtlsim
