// SPDX-License-Identifier: Apache-2.0
// Keys of multisample anti-aliasing (docs/antialiasing.md): raster.samples at the
// standard D3D11 / Vulkan positions (ref/sample_pattern.h) and raster.aa_mode.
#include "config/config.h"
#include "ref/sample_pattern.h"

namespace rastsim {

namespace {
bool is_sample_count(const ParamValue& v) { return valid_sample_count(int(std::get<int64_t>(v))); }
}  // namespace

void add_aa_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"raster.samples", T::Int, int64_t{1}, "samples", 1, 16, {},
               "Coverage samples a pixel, at the standard D3D11/Vulkan positions snapped to raster.coord_format; "
               "depth and colour are stored per sample and box-filtered (resolved) into the image. 1: no "
               "multisampling",
               is_sample_count, "1, 2, 4, 8 or 16"});
  s.push_back({"raster.aa_mode", T::Enum, std::string("msaa"), "", 1, 0, {"msaa", "ssaa"},
               "With raster.samples > 1: msaa shades once a pixel (at its centre) and writes that colour and depth "
               "to every covered sample; ssaa shades every covered sample at its own position"});
}

void validate_aa(const Config& cfg) {
  if (cfg.get_int("raster.samples") == 1) return;
  const std::string why = cfg.origin("raster.samples") + ": raster.samples = " +
                          std::to_string(cfg.get_int("raster.samples")) + " needs ";
  if (cfg.get_string("raster.traversal") == "scanline")
    throw ConfigError(why + "an exact traversal (tiled, bbox or hierarchical), but raster.traversal = scanline (" +
                      cfg.origin("raster.traversal") + ") finds pixel spans, not samples");
  if (cfg.get_string("interp.method") != "plane")
    throw ConfigError(why + "interp.method = plane (attributes at arbitrary sample points), but interp.method = " +
                      cfg.get_string("interp.method") + " (" + cfg.origin("interp.method") + ")");
}

}  // namespace rastsim
