// SPDX-License-Identifier: Apache-2.0
// One memory client of the ROP: a framebuffer surface (colour or depth) behind its own
// cache, with fast-clear flags and, for depth, plane compression; functional and untimed.
// It counts every access, hit, miss and byte moved (docs/memory.md, "Framebuffer,
// caches, fast clear and compression"). The reference ROP calls it a sample at a time;
// the timed model and the RTL testbench call the same class with the same stream, so
// their counts equal the reference's by construction.
//
// Bytes: a line fill reads the whole line, a write-back writes the whole line; with no
// cache (bytes = 0) every access is a miss that reads or writes its own sample's bytes.
// Fast clear (docs/memory.md has the rule): a clear flags every block and moves no byte;
// a fill whose every sample lies in flagged blocks reads nothing (the line is made of the
// clear value); the first write-back touching a flagged block unflags it and also writes
// the block's bytes outside the written-back line (the clear value: clear_fill_bytes).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "ref/memory/cache.h"
#include "ref/memory/surface_layout.h"

namespace rastsim {

class Framebuffer;

// One client's counters (stats keys memory.clients.<name>.*; docs/stats.md).
struct MemoryClientStats {
  uint64_t accesses = 0;           // sample reads and writes
  uint64_t hits = 0, misses = 0;   // accesses = hits + misses (no cache: every access misses)
  uint64_t evictions = 0;          // valid lines replaced by a miss
  uint64_t writebacks = 0;         // dirty lines written back (eviction or the frame-end flush)
  uint64_t bytes_read = 0, bytes_written = 0;  // to and from DRAM, every cause
  uint64_t fast_clear_blocks = 0;  // blocks flagged by fast clears
  uint64_t clear_fill_bytes = 0;   // clear value written materialising flagged blocks (in bytes_written)
  uint64_t compressed_blocks = 0;  // depth blocks written plane-encoded (clears included)
  uint64_t compressed_bytes = 0;   // their bytes (in bytes_written)
};

// One transfer between a surface and DRAM, as the functional model counts it: a line
// fill (read), a write-back of a line or block, a materialised fast-cleared block's
// clear value, a whole-surface clear, a streamed write.
struct MemoryTransfer {
  uint64_t address = 0;  // byte address of its first byte
  uint64_t bytes = 0;    // > 0
  bool write = false;
};

class SurfaceClient {
 public:
  SurfaceClient(const SurfaceLayout& layout, const CacheParams& cache, bool fast_clear, int block_width,
                int block_height);

  // Depth plane compression (depth_compression.h): the layout must be tiled by the block
  // and the cache lines one block each (RopMemory sets it up). Block contents are read
  // from `fb`'s depth at write-back.
  void compress_planes(const Framebuffer* fb, int depth_bits);

  // One access to sample s of pixel (x, y).
  void access(int x, int y, int s, bool write) {
    // The ROP reads and then writes a depth sample: the second access reuses the offset.
    if (x != last_x_ || y != last_y_ || s != last_s_)
      last_x_ = x, last_y_ = y, last_s_ = s, last_offset_ = layout_.offset_of(x, y, s);
    const uint64_t off = last_offset_;
    if (reported_) {  // transfers were reported since the previous access
      reported_ = false;
      if (on_access_after_transfer) on_access_after_transfer();
    }
    if (on_access) on_access(layout_.base() + off, write);
    ++stats_.accesses;
    if (cache_) return cached_access(off, write);
    ++stats_.misses;
    if (write) write_back_range(off, uint64_t(layout_.bytes_per_sample()));
    else fill(off, fill_range_bytes(off, uint64_t(layout_.bytes_per_sample())));
  }
  // A clear of the whole surface: fast (flags, 0 bytes) or every sample written. The
  // cache's lines are dropped, dirty or not: the clear overwrites them.
  void clear();
  // The frame end: every dirty line written back.
  void write_back_all();
  // The state `from` (a client of the same surface) has reached: its cache's lines, LRU
  // order and dirty bits, its fast-clear flags and plane-encoded blocks; not its counts or
  // callbacks. Frame sampling starts a timed run from a functional run's state with it
  // (model/fidelity/frame_sampled.h). Throws std::logic_error for another surface's.
  void take_state(const SurfaceClient& from);
  // Bytes written from `address` by a stream that bypasses the cache (the resolved image).
  void count_streamed_write(uint64_t address, uint64_t bytes) {
    stats_.bytes_written += bytes;
    report({address, bytes, true});
  }

  const MemoryClientStats& stats() const { return stats_; }
  const SurfaceLayout& layout() const { return layout_; }
  // Sees every access (byte address, write?), in order: for tests and access traces.
  std::function<void(uint64_t address, bool write)> on_access;
  // Sees every DRAM transfer the counts above are made of, in order (an access's
  // write-back and any block it materialises before its fill); the bytes of the
  // transfers sum to bytes_read and bytes_written. The timed model issues them.
  std::function<void(const MemoryTransfer&)> on_transfer;
  // Called at the first access after on_transfer has seen a transfer (before on_access),
  // not at the others: the timed model issues a surface's reported transfers then
  // (timing/rop_memory_port.h) without a call on every access.
  std::function<void()> on_access_after_transfer;

 private:
  // A cached access: a hit stays inline (SetAssocCache::access's repeat-line fast path),
  // a miss goes to cached_miss.
  void cached_access(uint64_t offset, bool write) {
    const uint64_t line = offset >> line_shift_;
    SetAssocCache::Victim victim;
    if (cache_->access(line, write, victim)) {
      ++stats_.hits;
      return;
    }
    cached_miss(line, victim);
  }
  void cached_miss(uint64_t line, const SetAssocCache::Victim& victim);
  // Counts a transfer at byte offset `offset` of the surface and reports it.
  void fill(uint64_t offset, uint64_t bytes) {
    stats_.bytes_read += bytes;
    transfer(offset, bytes, false);
  }
  void transfer(uint64_t offset, uint64_t bytes, bool write) { report({layout_.base() + offset, bytes, write}); }
  void report(const MemoryTransfer& t) {
    if (!on_transfer || t.bytes == 0) return;
    on_transfer(t);
    reported_ = true;
  }
  uint64_t fill_range_bytes(uint64_t offset, uint64_t len) const;  // a fill's DRAM reads
  void write_back_range(uint64_t offset, uint64_t len);
  void write_back_block(uint64_t block);  // compressed surface: one line = one block
  bool range_all_flagged(uint64_t offset, uint64_t len) const;
  template <class F>
  void for_each_block_piece(uint64_t offset, uint64_t len, F&& f) const;
  uint64_t block_bytes(size_t block) const;  // the block's samples inside the surface, bytes

  SurfaceLayout layout_;
  std::optional<SetAssocCache> cache_;
  int line_shift_ = 0;     // log2 of the cache's line bytes (a power of two)
  bool reported_ = false;  // a transfer went to on_transfer since the last access
  int last_x_ = -1, last_y_ = -1, last_s_ = -1;  // the previous access's sample (-1: none yet)
  uint64_t last_offset_ = 0;                      // ... and its byte offset
  bool fast_clear_;
  int block_w_, block_h_, blocks_x_, blocks_y_;
  std::vector<uint8_t> flagged_;  // per block: fast-cleared, not yet written to DRAM
  size_t n_flagged_ = 0;
  // Plane compression: the framebuffer the block contents come from, and per block
  // whether DRAM holds it plane-encoded.
  const Framebuffer* fb_ = nullptr;
  int depth_bits_ = 0;
  std::vector<uint8_t> plane_stored_;
  std::vector<std::pair<size_t, uint64_t>> touched_;  // write_back_range's scratch: block, bytes in the range
  MemoryClientStats stats_;
};

}  // namespace rastsim
