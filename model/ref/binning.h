// SPDX-License-Identifier: Apache-2.0
// The binned (tile-based) reference pipeline, functional and untimed (pipeline.mode =
// binned; docs/binning.md has the rules, the parameter buffer's layout and byte sizes).
//
// Binning pass: each set-up triangle, in submission order, is stored once as a
// primitive record in the parameter buffer (DRAM) and listed in the bins its clipped box
// overlaps (bin.binning = bbox) or where traverse() finds a covered sample (exact). A
// clear is a clear record every bin reads, numbered in the same sequence as the
// triangles' records. Render pass, bin by bin in raster order: the bin's list and the
// clears merged by record number, each triangle drawn by the renderer's own draw() with
// its box clipped to the bin (the same traversal, interpolation and ROP), each clear
// applied to the bin's rectangle; then the bin is stored once. When the parameter buffer cannot
// take the next record, every bin of what it holds is rendered first (an overflow pass:
// colour and depth stored, reloaded by the next pass) and the buffer starts empty.
//
// The tile buffer: the samples of the bin's rectangle in the Framebuffer stand for it
// while the bin renders (no copy: the same values); its loads and stores are counted.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "ref/framebuffer.h"
#include "ref/memory/bin_memory.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "ref/tri_setup.h"
#include "ref/traverse.h"

namespace rastsim {

// Parameter buffer record sizes, bytes (docs/binning.md, "Parameter buffer").
inline constexpr uint64_t kBinPrimitiveRecordBytes = 64;  // one set-up triangle
inline constexpr uint64_t kBinClearRecordBytes = 16;      // one clear (colour or depth)
inline constexpr uint64_t kBinListEntryBytes = 4;         // one bin list entry

// The binned pipeline's counts (stats keys bins, primitives_per_bin_mean, bin_overflows,
// dram_bytes_geometry, dram_bytes_framebuffer; docs/stats.md).
struct BinStats {
  bool enabled = false;             // pipeline.mode = binned
  uint64_t bins = 0;                // bins on the screen (ceil(W / bin.width) x ceil(H / bin.height))
  uint64_t triangle_entries = 0;    // triangle entries over every bin list of every pass
  uint64_t bin_overflows = 0;       // passes forced by a full parameter buffer
  uint64_t bins_rendered = 0;       // bin render passes run (a bin may render once a pass)
  uint64_t geometry_bytes_written = 0, geometry_bytes_read = 0;        // the parameter buffer
  uint64_t framebuffer_bytes_written = 0, framebuffer_bytes_read = 0;  // bin stores and loads
  uint64_t dram_bytes_geometry() const { return geometry_bytes_written + geometry_bytes_read; }
  uint64_t dram_bytes_framebuffer() const { return framebuffer_bytes_written + framebuffer_bytes_read; }
  double primitives_per_bin_mean() const { return bins ? double(triangle_entries) / double(bins) : 0.0; }
};

// The bytes of one bin's pixels of a surface: colour 4 a sample, depth 2 (raster.
// depth_bits <= 16) or 4 a sample, as the memory system's surfaces (docs/memory.md).
inline uint64_t bin_depth_sample_bytes(int depth_bits) { return uint64_t(depth_bytes_per_sample(depth_bits)); }

// A clear record's content: the colour to (r, g, b, 255), or the depth to z.
struct BinClear {
  bool depth = false;
  uint8_t r = 0, g = 0, b = 0;
  uint32_t z = 0;
};
// Applies clear `c` to every sample of pixels `r` of `fb` (a bin's rectangle: the tile
// buffer's samples), as a bin's render pass does.
void clear_bin_rect(Framebuffer& fb, const PixelRect& r, const BinClear& c);

// Bytes a bin moves, colour and depth (a load before its pass or a store after it).
struct BinBytes {
  uint64_t color = 0, depth = 0;
  uint64_t total() const { return color + depth; }
};

class Binner {
 public:
  // draw(tri, walk): the renderer draws tri with walk's box (tri's, clipped to a bin).
  using DrawFn = std::function<void(const SetupTriangle& tri, const SetupTriangle& walk)>;
  // `mem` (memory.model != fixed): the parameter buffer's and the bins' transfers at
  // their addresses (ref/memory/bin_memory.h); null: bytes counted only.
  Binner(const RasterState& st, const TraversalParams& tp, Framebuffer& fb, DrawFn draw, BinStats& stats,
         BinMemory* mem = nullptr);

  // A set-up triangle (accepted by setup) of command `loc`, in submission order.
  void add_triangle(const SetupTriangle& tri, const SourceLoc& loc);
  // A clear of the colour to (r, g, b, 255), or of the depth to z (raster.depth_bits).
  void add_clear_color(uint8_t r, uint8_t g, uint8_t b, const SourceLoc& loc);
  void add_clear_depth(uint32_t z, const SourceLoc& loc);
  // The frame's last pass: every bin with a list, and every bin never stored, rendered
  // and stored (colour resolved when raster.samples > 1).
  void finish();

  // What a timed model sees of the render pass (sc/binning.h); unset members: nothing.
  // begin_bin before a bin's loads (the bytes it loads), clear instead of writing the
  // framebuffer (the timed ROP applies it in its place in the stream), end_bin after the
  // bin's stores (the bytes it stores; colour resolved on the last pass when
  // raster.samples > 1). The render pass calls them in order, bin by bin.
  struct Hooks {
    std::function<void(int bin, const PixelRect& r, BinBytes load)> begin_bin;
    std::function<void(const BinClear& c, const PixelRect& r)> clear;
    std::function<void(int bin, const PixelRect& r, bool final_pass, BinBytes store)> end_bin;
  };
  void set_hooks(Hooks h) { hooks_ = std::move(h); }
  // The triangles the parameter buffer holds, in record order (draw()'s `tri` is one).
  const std::vector<SetupTriangle>& held() const { return tris_; }
  // The bins a box overlaps (bbox's list; exact's candidates): bins_x0 .. x1 - 1 by y0 .. y1 - 1.
  PixelRect bin_range(const PixelRect& box) const;

  int bins_x() const { return nx_; }
  int bins_y() const { return ny_; }
  PixelRect bin_rect(int b) const;  // clipped to the screen
  // The bins listing triangle tri under the configured rule (exposed for the tests).
  std::vector<int> bins_of(const SetupTriangle& tri) const;

 private:
  struct ClearRecord {
    uint32_t seq = 0;  // records before it in the buffer: it applies after those triangles
    BinClear clear;
    uint64_t offset = 0;  // its byte offset in the parameter buffer
  };

  void reserve(uint64_t bytes, const SourceLoc& loc);
  void add_clear(ClearRecord c, const SourceLoc& loc);
  void render_pass(bool final_pass);
  void render_bin(int b, bool final_pass);
  BinBytes load_bytes(const PixelRect& r, bool color, bool depth) const;
  BinBytes store_bytes(const PixelRect& r, bool final_pass, bool depth) const;
  void load_bin(const PixelRect& r, BinBytes bytes);  // counted, and its transfers
  void store_bin(const PixelRect& r, bool final_pass, BinBytes bytes);

  RasterState st_;
  TraversalParams tp_;
  Framebuffer& fb_;
  DrawFn draw_;
  Hooks hooks_;
  BinStats& stats_;
  int nx_ = 1, ny_ = 1;
  uint64_t used_ = 0;  // parameter buffer bytes holding records and entries
  BinMemory* mem_;
  uint32_t seq_ = 0;  // records (triangles and clears) in the buffer, in submission order
  uint64_t record_bytes_ = 0;  // bytes of records in the buffer (the next record's offset)
  uint64_t entries_ = 0;       // list entries in the buffer (the next entry's number)
  struct Entry {
    uint32_t tri;    // index into tris_
    uint32_t number; // entry number of the pass (its address: BinMemory::entry_address)
  };
  std::vector<SetupTriangle> tris_;
  std::vector<uint32_t> tri_seq_;                           // each triangle's record number
  std::vector<uint64_t> tri_offset_;                        // each triangle's record's byte offset
  std::vector<ClearRecord> clears_;                         // every bin reads them all
  std::vector<std::vector<Entry>> lists_;                   // per bin: its entries, in order
  std::vector<uint8_t> color_stored_, depth_stored_;        // per bin: in DRAM from an earlier pass this frame
};

// Throws SceneError naming `cmd` when pipeline.mode = binned cannot draw it yet: 2D
// drawing, a texture bound, clip.method = homogeneous (docs/binning.md, "Not yet").
void check_binned_command(const Command& cmd, const RasterState& st);

}  // namespace rastsim
