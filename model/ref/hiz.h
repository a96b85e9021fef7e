// SPDX-License-Identifier: Apache-2.0
// Hierarchical Z (depth.hiz, docs/depth-culling.md): a per-block depth bound kept beside
// the depth buffer, tested by coarse raster against each tile's conservative depth range
// so whole tiles fail (culled) or, with "minmax", pass (accepted: no per-pixel depth
// read) before fine raster. Functional and exact: the image is the one without it.
//
// Blocks: depth.hiz_block = B px squares aligned to the framebuffer origin, row-major.
// A block holds (D = raster.depth_bits):
//   - its bound(s): zmax >= every stored depth of the block ("max" and "minmax"), zmin <=
//     every stored depth ("minmax" only), D bits each;
//   - the layer: a B x B mask of the pixels written since the layer started and the
//     largest (and smallest, minmax) depth written since, D bits each.
// Update rule, on every depth write of z at a pixel of the block (any depth function):
//   zmax = max(zmax, z); zmin = min(zmin, z); mask |= pixel; lmax = max(lmax, z);
//   lmin = min(lmin, z); when the mask covers every on-screen pixel of the block, each
//   pixel's depth was written during the layer, so lies in [lmin, lmax]: zmax = min(zmax,
//   lmax), zmin = max(zmin, lmin), and the layer restarts empty. So a bound only tightens
//   (max falls, min rises) when the whole block is known written; a depth clear to c
//   sets zmin = zmax = c exactly.
// Entry encoding: the bits above, 2D + B^2 (max) or 4D + B^2 (minmax), padded to the
// next power of two of bytes (entry_bytes). The first floor(depth.hiz_bytes /
// entry_bytes) blocks (row-major) are on chip; the rest are spilled to DRAM at byte
// offset (i - on_chip) x entry_bytes of the table: a test of a spilled block reads its
// entry, a tile's update of it reads and writes it (memory.clients.hiz).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "ref/coarse_raster.h"
#include "ref/framebuffer.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "ref/tri_setup.h"

namespace rastsim {

// The conservative depth range of a triangle's fragments over a tile footprint (one
// sample a pixel, plane interpolation): every fragment z = round_half_up(num / area2)
// with num = E1 z0 + E2 z1 + E0 z2 linear in the sample position, so over the
// footprint's pixel centres num lies between its values at the four corner centres;
// lo = max(min z_k, floor(num_min / area2)), hi = min(max z_k, ceil(num_max / area2))
// (round_half_up of a value in [a, b] lies in [floor a, ceil b]; inside the triangle the
// rational lies between the vertex depths).
// The spilled table's memory client (memory.clients.hiz).
inline constexpr const char* kHizClient = "hiz";

// lo and hi are the exact bounds clamped to [-1, 2^D] (signed: at a corner outside the
// triangle the plane can leave the depth range; clamped there, every comparison with a
// stored bound in [0, 2^D - 1] is the exact one, which the RTL's multiply-compare test,
// rtl/rast_hiz_test.sv, makes without dividing).
struct DepthRange {
  int64_t lo = 0, hi = 0;
};
DepthRange tile_depth_range(const SetupTriangle& t, const PixelRect& fp, int frac_bits);

// A tile's Hi-Z outcome: drawn as usual, culled (every fragment fails the depth test),
// or accepted (every fragment passes it: the ROP need not read the stored depth).
enum class HizDecision { Draw, Culled, Accepted };

// A drawn tile's depth write to a spilled block (HizTracker::apply, for the timed model's
// flush, timing/hiz_memory_port.h): the written pixel's index among the tile's covered
// pixels in row-major order (the fragment's index in the ROP's batch) and the block.
struct HizSpillWrite {
  uint32_t fragment = 0;
  int32_t block = 0;
};

// The counts of the Hi-Z unit (stats keys tiles_culled_hiz, tiles_accepted_hiz,
// fragments_culled_hiz, memory.clients.hiz.*).
struct HizStats {
  bool enabled = false;          // depth.hiz != off and the run can use it (single sample)
  uint64_t tiles_tested = 0;     // tiles coarse raster tested against the table
  uint64_t tiles_culled = 0, tiles_accepted = 0;
  uint64_t fragments_culled = 0;  // covered pixels of the culled tiles
  uint64_t block_updates = 0;     // (tile, block) updates written back
  uint64_t layer_completions = 0;  // blocks whose layer covered them (a bound tightened)
  uint64_t dram_reads = 0, dram_writes = 0;  // spilled entries moved
  uint64_t bytes_read = 0, bytes_written = 0;
  HizStats& operator+=(const HizStats& o);
};

class HizTable {
 public:
  // mode Max or MinMax; block a power of two; depth cleared to the largest value.
  HizTable(HizMode mode, int block, int64_t onchip_bytes, int width, int height, int depth_bits);

  int entry_bytes() const { return entry_bytes_; }
  int64_t blocks() const { return int64_t(nx_) * ny_; }
  int64_t onchip_blocks() const { return onchip_; }
  // Block i (row-major) is past the on-chip part; its entry's byte address (spilled only).
  bool spilled(int64_t i) const { return i >= onchip_; }
  uint64_t entry_address(int64_t i) const { return dram_base + uint64_t(i - onchip_) * uint64_t(entry_bytes_); }
  // fp overlaps a spilled block (its last block, the largest index, is one).
  bool spills(const PixelRect& fp) const {
    return spilled(index((fp.x1 - 1) >> log2B_, (fp.y1 - 1) >> log2B_));
  }

  // The decision for fragments of depth range r over footprint fp under `func`; counts
  // the entry reads of spilled blocks. Draw for a function Hi-Z does not handle, and in
  // place of an accept when !may_accept (a lagged table's busy blocks: HizTracker::test_lagged).
  HizDecision test(const PixelRect& fp, DepthRange r, DepthFunc func, bool may_accept = true);
  // The entry reads of fp's spilled blocks a test makes (test() makes them too): a lagged
  // test against another table still reads this table's entries (the traffic is the same).
  void read_spilled(const PixelRect& fp);
  // One depth write of z at pixel (x, y): the update rule above (on chip at once; the
  // block is marked for flush()).
  void write(int x, int y, uint32_t z);
  // A depth clear to z: every bound exact.
  void clear(uint32_t z);
  // The end of a tile (or of a command): every block written since is written back once.
  void flush();
  // Every bound of the blocks fp overlaps (farthest max, nearest min): the tests' view.
  DepthRange bounds(const PixelRect& fp) const;

  HizStats stats;
  // Called at every access of a spilled entry, in order: its byte address (dram_base +
  // (i - onchip_blocks) x entry_bytes), entry_bytes, and whether it is the write of a
  // flush's read-modify-write. Unset: nothing called (render). The timed model's memory
  // client (timing/hiz_memory_port.h) sets it.
  std::function<void(uint64_t address, uint64_t bytes, bool write)> on_access;
  uint64_t dram_base = 0;  // depth.hiz_base

 private:
  void spilled_access(int i, bool write);
  struct Block {
    uint32_t zmin = 0, zmax = 0, lmin = 0, lmax = 0;
    std::array<uint64_t, 4> mask{};  // B^2 <= 256 bits, pixel (i, j) of the block at bit j B + i
    int written = 0;             // bits set in mask
    bool dirty = false;
  };
  int index(int bx, int by) const { return by * nx_ + bx; }
  int full_count(int bx, int by) const;  // the block's on-screen pixels

  HizMode mode_;
  int B_, log2B_, nx_, ny_, width_, height_, depth_bits_, entry_bytes_;
  int64_t onchip_;
  std::vector<Block> blocks_;
  std::vector<int> dirty_;
};

// Functional-first Hi-Z for the models that walk tiles ahead of a ROP (the timed coarse
// raster, sc/coarse_raster.h, and estimate's walk): the depth buffer and table the
// reference would have at each tile, kept by applying each drawn tile's depth writes
// (one sample, the plane depths, the state's function and raster.depth_write) at once,
// in walk order: a zero-lag table (docs/depth-culling.md, "The timed model").
// One depth write the ROP will make (pixel, depth): a lagged table's update.
struct HizWrite {
  int x = 0, y = 0;
  uint32_t z = 0;
};

class HizTracker {
 public:
  explicit HizTracker(const RasterState& st);
  // The decision for tile footprint fp (class cls, not rejected) of t; a culled tile's
  // covered pixels counted into table.stats.fragments_culled (as the reference's filter).
  HizDecision test(const SetupTriangle& t, const PixelRect& fp, TileClass cls);
  // depth.hiz_sync = lagged (docs/depth-culling.md "Lagged"): the decision against
  // `stale`, the table as the ROP has written it (a prefix of the writes `table` holds),
  // its counts in stale.stats (the culled fragments, and the spilled entries' reads, which
  // the test makes as test() does, in table.stats). A cull from stale
  // bounds is one the zero-lag table makes too (stored depths move one way between
  // clears); an accept is made only when `idle` (no tile in flight touches fp's blocks,
  // so stale holds every write to them), else the tile is drawn.
  HizDecision test_lagged(const SetupTriangle& t, const PixelRect& fp, TileClass cls, HizTable& stale, bool idle);
  // A drawn tile's depth writes, then its blocks flushed; each write also appended to
  // `writes` when given (a lagged table applies them when the ROP has), and its writes to
  // spilled blocks to `spilled` when given, in order (the flush engine's, sc/hiz_flush.h).
  void apply(const SetupTriangle& t, const PixelRect& fp, TileClass cls, std::vector<HizWrite>* writes = nullptr,
             std::vector<HizSpillWrite>* spilled = nullptr);
  // A state command: a depth clear resets the depth and the table.
  void state(const Command& cmd);
  // The value a depth clear command sets (D bits), none for any other command.
  std::optional<uint32_t> depth_clear(const Command& cmd) const;
  HizTable table;

 private:
  void count_culled(const SetupTriangle& t, const PixelRect& fp, TileClass cls);
  RasterState st_;
  Framebuffer depth_;  // one sample, colour unused
};

// True when the Hi-Z test may run for a draw with this state (docs/depth-culling.md):
// single sample, tiled traversal, plane interpolation (a clip.method = homogeneous
// command has no tile walk and is never tested), and a depth
// function the mode handles (max: less, lequal; minmax: also greater, gequal).
bool hiz_applies(const RasterState& st);

}  // namespace rastsim
