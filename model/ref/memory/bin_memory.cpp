// SPDX-License-Identifier: Apache-2.0
#include "ref/memory/bin_memory.h"

#include <algorithm>

#include "ref/framebuffer.h"
#include "ref/memory/rop_memory.h"
#include "ref/raster_state.h"

namespace rastsim {

BinMemory::BinMemory(const MemoryParams& p, int width, int height, int samples, int depth_bits, uint64_t pb_base,
                     uint64_t pb_bytes)
    : color_(color_surface_layout(p, width, height, samples)),
      depth_(depth_surface_layout(p, width, height, samples, depth_bits)),
      resolved_(color_surface_layout(p, width, height, 1)), pb_base_(pb_base), pb_bytes_(pb_bytes) {}

void BinMemory::transfer(MemoryClientStats& s, uint64_t address, uint64_t bytes, bool write) {
  ++s.accesses;
  ++s.misses;  // no cache: every transfer goes to DRAM
  (write ? s.bytes_written : s.bytes_read) += bytes;
  if (on_transfer) on_transfer(&s == &binning_ ? Client::Binning : Client::TileStore, {address, bytes, write});
}

// The bin's pixels in address order (each pixel's samples together, B bytes a sample),
// merged into runs of consecutive addresses: one transfer a run (a linear surface: a bin
// row; a tiled one: a row of whole tiles when the bin is a multiple of the tile).
void BinMemory::surface(const SurfaceLayout& l, const PixelRect& r, bool write) {
  const uint64_t pixel_bytes = uint64_t(l.samples()) * uint64_t(l.bytes_per_sample());
  addresses_.clear();
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) addresses_.push_back(l.address_of(x, y, 0));
  std::sort(addresses_.begin(), addresses_.end());
  uint64_t start = 0, end = 0;
  for (uint64_t a : addresses_) {
    if (a != end) {
      if (end > start) transfer(tile_store_, start, end - start, write);
      start = a;
    }
    end = a + pixel_bytes;
  }
  if (end > start) transfer(tile_store_, start, end - start, write);
}

}  // namespace rastsim
