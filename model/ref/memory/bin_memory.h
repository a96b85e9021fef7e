// SPDX-License-Identifier: Apache-2.0
// The binned pipeline's memory clients (pipeline.mode = binned with memory.model !=
// fixed; docs/binning.md, "Memory clients"), functional and untimed:
// - `binning` (kBinningClient): the parameter buffer at bin.parameter_buffer_base. Records
//   (triangles 64 bytes, clears 16) are packed upwards from the base in submission
//   order; list entries (4 bytes) downwards from base + bin.parameter_buffer_bytes in the
//   order the binning pass writes them (a triangle's bins in raster order). A pass's
//   records and entries never share a byte (the Binner's reservation keeps their sum
//   within the buffer) and every overflow pass starts both ends afresh.
// - `tile_store` (kTileStoreClient): a bin's loads and stores of the colour and depth
//   surfaces, at the surfaces' own addresses and layout (ref/memory/surface_layout.h,
//   the ROP's surfaces: memory.color_base, memory.depth_base, memory.fb_layout); a
//   resolved colour store goes to the one-sample image at memory.color_base, as the
//   immediate ROP's resolved image. Uncompressed, no fast clear (a bin clears on chip).
// Each transfer is one run of consecutive addresses (a bin's pixels in address order,
// merged); on_transfer sees them in order, so a timed
// model can issue them; their bytes sum to the client's bytes_read and bytes_written.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "ref/memory/memory_params.h"
#include "ref/memory/surface_client.h"
#include "ref/memory/surface_layout.h"

namespace rastsim {

struct PixelRect;

inline constexpr const char* kBinningClient = "binning";
inline constexpr const char* kTileStoreClient = "tile_store";

class BinMemory {
 public:
  enum class Client { Binning, TileStore };
  // Surfaces of width x height x samples (depth_bits: 2 or 4 bytes a sample); the
  // parameter buffer of `pb_bytes` bytes at `pb_base`.
  BinMemory(const MemoryParams& p, int width, int height, int samples, int depth_bits, uint64_t pb_base,
            uint64_t pb_bytes);

  // The parameter buffer: `bytes` of a record at byte `offset` from the base; list entry
  // number `k` of the pass (4 bytes at base + pb_bytes - 4 (k + 1)).
  void record(uint64_t offset, uint64_t bytes, bool write) { transfer(binning_, pb_base_ + offset, bytes, write); }
  void entry(uint64_t k, bool write) { transfer(binning_, entry_address(k), 4, write); }
  uint64_t entry_address(uint64_t k) const { return pb_base_ + pb_bytes_ - 4 * (k + 1); }

  // A bin's pixels `r` (clipped to the screen) loaded or stored: every sample of the
  // colour or depth surface, or (resolved) one colour sample a pixel of the one-sample image.
  void color(const PixelRect& r, bool write) { surface(color_, r, write); }
  void depth(const PixelRect& r, bool write) { surface(depth_, r, write); }
  void resolved_color(const PixelRect& r) { surface(resolved_, r, true); }

  const MemoryClientStats& binning_stats() const { return binning_; }
  const MemoryClientStats& tile_store_stats() const { return tile_store_; }
  const SurfaceLayout& color_layout() const { return color_; }
  const SurfaceLayout& depth_layout() const { return depth_; }

  // Sees every transfer, in order, with its client.
  std::function<void(Client, const MemoryTransfer&)> on_transfer;

 private:
  void surface(const SurfaceLayout& l, const PixelRect& r, bool write);
  void transfer(MemoryClientStats& s, uint64_t address, uint64_t bytes, bool write);

  SurfaceLayout color_, depth_, resolved_;
  uint64_t pb_base_, pb_bytes_;
  MemoryClientStats binning_, tile_store_;
  std::vector<uint64_t> addresses_;  // scratch: one bin's pixel addresses
};

}  // namespace rastsim
