// SPDX-License-Identifier: Apache-2.0
// Keys of multisample anti-aliasing (docs/antialiasing.md): raster.samples at the
// standard D3D11 / Vulkan positions (ref/sample_pattern.h), raster.aa_mode, and
// raster.max_samples, the hardware's build-time maximum (the RTL's MaxSamples).
#include "config/config_schema.h"
#include "ref/sample_pattern.h"

namespace rastsim {

namespace {
bool is_sample_count(const ParamValue& v) { return valid_sample_count(int(std::get<int64_t>(v))); }
}  // namespace

void add_aa_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"raster.samples", T::Int, int64_t{1}, "samples", 1, kMaxSamples, {},
               "Coverage samples a pixel, at the standard D3D11/Vulkan positions snapped to raster.coord_format; "
               "depth and colour are stored per sample and box-filtered (resolved) into the image. 1: no "
               "multisampling",
               is_sample_count, "1, 2, 4, 8 or 16"});
  s.push_back({"raster.aa_mode", T::Enum, std::string("msaa"), "", 1, 0, {"msaa", "ssaa"},
               "With raster.samples > 1: msaa shades once a pixel (at its centre) and writes that colour and depth "
               "to every covered sample; ssaa shades every covered sample at its own position"});
  // The RTL's MaxSamples (docs/rtl.md): the sample mask bits a pixel in the pixel FIFO and
  // the sample tests of the fine raster, so its area (docs/area.md). At least 2: the RTL
  // indexes a pixel's samples with $clog2(MaxSamples) bits (rtl/rast_interpolate.sv), which
  // is no bits at 1. The default is the schema's largest raster.samples, so the shipped
  // configs' verilated models run every sample count.
  s.push_back({"raster.max_samples", T::Int, int64_t{kMaxSamples}, "samples", 2, kMaxSamples, {},
               "The largest sample count the hardware supports; a build-time RTL parameter (MaxSamples: sample "
               "mask bits a pixel in the pixel FIFO, sample tests in the fine raster). raster.samples may be any "
               "count up to it (a run-time input of the RTL). At least 2 (the RTL's minimum)",
               is_sample_count, "2, 4, 8 or 16"});
}

void validate_aa(const Config& cfg) {
  if (cfg.get_int("raster.samples") > cfg.get_int("raster.max_samples"))
    throw ConfigError(cfg.origin("raster.samples") + ": raster.samples = " + std::to_string(cfg.get_int("raster.samples")) +
                      " exceeds raster.max_samples = " + std::to_string(cfg.get_int("raster.max_samples")) + " (" +
                      cfg.origin("raster.max_samples") +
                      "), the largest sample count the hardware is built for: raise raster.max_samples or lower "
                      "raster.samples");
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
