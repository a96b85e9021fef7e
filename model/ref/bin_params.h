// SPDX-License-Identifier: Apache-2.0
// The binned (tile-based) pipeline's parameters (config keys pipeline.mode, bin.*;
// docs/binning.md). A plain struct of RasterState; the renderer is ref/binning.h.
#pragma once

#include <cstdint>

namespace rastsim {

enum class PipelineMode { Immediate, Binned };
enum class BinningRule { Bbox, Exact };  // bin.binning: which bins list a triangle

struct BinParams {
  PipelineMode mode = PipelineMode::Immediate;
  int width = 0, height = 0;              // bin.width, bin.height: px, powers of two in 8 .. 128
  uint64_t tile_buffer_bytes = 0;         // on-chip colour + depth of one bin, every sample
  uint64_t parameter_buffer_bytes = 0;    // DRAM bytes for primitive records + per-bin lists
  uint64_t parameter_buffer_base = 0;     // byte address of the parameter buffer
  BinningRule rule = BinningRule::Bbox;
  // What a bin loads before and stores after its render pass (per frame). A load reads
  // the bin's samples from the framebuffer in DRAM; without it the tile buffer starts from
  // the frame's initial value (colour: opaque black, depth: the far plane). Passes forced
  // by an overflow always store colour and depth and the next pass reloads them.
  bool load_color = false, load_depth = false;
  bool store_depth = false;  // colour is always stored (the image)
};

}  // namespace rastsim
