// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/rop_memory.h"

#include "ref/framebuffer.h"

namespace rastsim {

RopMemory::RopMemory(const MemoryParams& p, const Framebuffer& fb, int depth_bits)
    : color(color_surface_layout(p, fb.width, fb.height, fb.samples), p.color_cache, p.fast_clear, p.block_width,
            p.block_height),
      depth(depth_surface_layout(p, fb.width, fb.height, fb.samples, depth_bits),
            depth_cache_params(p, fb.samples, depth_bits), p.fast_clear, p.block_width, p.block_height),
      width_(fb.width), height_(fb.height), samples_(fb.samples) {
  if (p.depth_compression == DepthCompression::Plane) depth.compress_planes(&fb, depth_bits);
}

void RopMemory::finish() {
  if (samples_ > 1)
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        for (int s = 0; s < samples_; ++s) color.access(x, y, s, false);
  color.write_back_all();
  depth.write_back_all();
  // The resolved image goes to the colour surface's base (the one-sample front buffer
  // over the start of the multisample surface).
  if (samples_ > 1)
    color.count_streamed_write(color.layout().base(), uint64_t(width_) * uint64_t(height_) * kColorBytesPerSample);
}

}  // namespace rastsim
