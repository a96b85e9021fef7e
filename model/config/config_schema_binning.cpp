// SPDX-License-Identifier: Apache-2.0
// Keys of the binned (tile-based) pipeline: pipeline.mode and bin.* (docs/binning.md).
// The cross-key check (a bin's colour + depth must fit bin.tile_buffer_bytes) is in
// raster_state_config.cpp, where the sample count and depth bits are known.
#include "config/config_schema.h"

namespace rastsim {

void add_binning_params(std::vector<ParamDef>& s) {
  using T = ParamType;
  s.push_back({"pipeline.mode", T::Enum, std::string("immediate"), "", 1, 0, {"immediate", "binned"},
               "immediate: triangles rasterised as submitted, into the framebuffer; binned: a binning pass lists "
               "each set-up triangle in the screen bins it touches (parameter buffer in DRAM), then each bin is "
               "rendered into an on-chip tile buffer and stored once (docs/binning.md; render only)"});
  s.push_back({"bin.width", T::Int, int64_t{32}, "px", 8, 128, {}, "Bin width of pipeline.mode = binned",
               is_power_of_two, "a power of two"});
  s.push_back({"bin.height", T::Int, int64_t{32}, "px", 8, 128, {}, "Bin height of pipeline.mode = binned",
               is_power_of_two, "a power of two"});
  s.push_back({"bin.tile_buffer_bytes", T::Int, int64_t{262144}, "bytes", 1, double(int64_t{1} << 30), {},
               "On-chip tile buffer: colour (4 bytes) + depth (2 bytes for raster.depth_bits <= 16, else 4) of "
               "every sample of one bin must fit"});
  s.push_back({"bin.parameter_buffer_bytes", T::Int, int64_t{16} << 20, "bytes", 64, double(int64_t{1} << 34), {},
               "DRAM parameter buffer: primitive records (64 bytes) + bin list entries (4 bytes) + clear records "
               "(16 bytes); when full every bin of what it holds is rendered (bin_overflows) and it starts empty"});
  s.push_back({"bin.parameter_buffer_base", T::Int, int64_t{1} << 31, "bytes", 0, double(int64_t{1} << 40), {},
               "Byte address of the parameter buffer", is_page_multiple, "a multiple of 4096"});
  s.push_back({"bin.binning", T::Enum, std::string("bbox"), "", 1, 0, {"bbox", "exact"},
               "bbox: a triangle is listed in every bin its clipped bounding box overlaps; exact: only in the bins "
               "where the raster's own traversal finds a covered sample"});
  s.push_back({"bin.load_color", T::Bool, false, "", 1, 0, {},
               "Each bin reads its colour from DRAM before its first pass (false: starts from the frame's initial "
               "opaque black; the image is the same, only bytes differ)"});
  s.push_back({"bin.load_depth", T::Bool, false, "", 1, 0, {},
               "Each bin reads its depth from DRAM before its first pass (false: starts at the far plane)"});
  s.push_back({"bin.store_depth", T::Bool, false, "", 1, 0, {},
               "Each bin writes its depth to DRAM after its last pass (false: discarded; colour is always stored)"});
}

}  // namespace rastsim
