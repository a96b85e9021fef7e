// SPDX-License-Identifier: Apache-2.0
// Binned mode (pipeline.mode = binned) in co-simulation (docs/rtl.md "Tile buffer",
// docs/binning.md "RTL"): the testbench is the binner, the RTL renders each bin into its
// tile buffer (rtl/rast_tile_buffer.sv in rast_top).
//
// - The binning pass stays in C++: the reference's Binner (ref/binning.h) takes the
//   stream's set-up triangles and clears in order, as the SystemC binner stage drives it
//   (sc/binning.cpp), so which bins list a triangle, the parameter buffer's transfers,
//   overflow passes and every load and store are the reference's. BinProgram (at set-up)
//   records what it does as a program of steps: take a stream item from primitive
//   assembly (the binner's cycles: max(setup.interval_cycles, max(1, C)) a triangle whose
//   clipped box overlaps C bins, 1 a state command; its parameter-buffer writes posted),
//   a bin's list prefetch (its reads issued together, waited for), and the items fed to
//   rast_top's triangle port, one a cycle: a begin marker, each clear of the bin (a clear
//   marker) and listed triangle (clip rectangle = its scissor's clipped to the bin, so
//   setup's box is the reference's walk, tri.bbox clipped to the bin) in record order,
//   an end marker; at the end, the end-of-frame marker (a pass). The expected fragments
//   are the reference's draws in that order (ref/pipeline.cpp draw(tri, walk)).
// - TbBinner (at run time) plays the program and serves the tile buffer's memory port
//   (tl_*): a store's beats written to the testbench's framebuffer, a load's beats read
//   from it and answered in order; with memory.model = dram the bin's tile_store
//   transfers (the reference's, at its surfaces' addresses) are issued when the ROP takes
//   the begin (reads, waited for: load beat k of n answers at max(its issue + 1,
//   arrival - (n - 1 - k)), so the last at max(the beats' end, arrival) as the SystemC
//   ROP's max(ceil(L / R), arrival - t0)) or end marker (posted writes), and the
//   binning client's writes and prefetch reads at the binner's steps. It checks each
//   load and store moves every sample of its surfaces in the beats of the tile buffer's
//   row rule.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ref/memory/rop_memory.h"
#include "ref/memory/surface_client.h"
#include "ref/raster_state.h"
#include "ref/scene.h"
#include "ref/tri_setup.h"
#include "timing/memory_system.h"

namespace rastsim::rtlsim {

struct TbSetup;
struct TbItem;
class RastPorts;

// A bin command on rast_top's command port (rast_tile_buffer.sv): op 4 begins the bin
// (value bit 0: colour loaded, bit 1: depth loaded), 5 ends it (bits: stored; bit 2: the
// colour resolved, the frame's last pass with raster.samples > 1), 1 and 2
// clear it (value: the clear word), 0 passes (the end of frame).
struct TbBinMarker {
  int op = 0;
  uint32_t value = 0;
  int rect[4] = {};  // the bin: x0, y0, x1, y1 (half-open px, clipped to the screen)
  std::vector<MemoryTransfer> transfers;  // tile_store: the begin's loads, the end's stores
  uint64_t beats = 0;                     // beats of its load or store by the tile buffer's row rule
};
// One step of the testbench's binner.
struct TbBinOp {
  enum Kind { Take, Prefetch, Feed } kind = Take;
  size_t item = 0;     // Take: the stream item assembly hands over; Feed: the item fed to rast_top
  uint64_t cycles = 1; // Take: the binner's cycles
  std::vector<MemoryTransfer> transfers;  // Take: parameter-buffer writes; Prefetch: its reads
};
struct TbBinning {
  std::vector<TbBinMarker> markers;
  std::vector<TbBinOp> ops;
  MemoryStats memory;  // the reference's binning and tile_store counts (memory.model = dram)
};

// Beats of a tile buffer's load or store of bin `rect`'s surfaces in `flags` (bit 0
// colour, bit 1 depth, bit 2 colour resolved): each row of w S samples (resolved colour:
// w pixels) in beats of port_bytes / 4 colour or port_bytes / depth bytes depth samples
// (rast_tile_buffer.sv's walk).
uint64_t tile_beats(const int rect[4], uint32_t flags, int samples, int depth_bits, int port_bytes);

// Builds setup.binning and the render pass's items and expected fragments (set-up time).
class BinProgram {
 public:
  BinProgram(TbSetup& s, int tile_size);
  ~BinProgram();
  BinProgram(const BinProgram&) = delete;
  BinProgram& operator=(const BinProgram&) = delete;
  // Stream item `item` reaches the binner: a triangle, `tri` when setup accepts it.
  void triangle(size_t item, const SetupTriangle* tri, const SourceLoc& loc);
  // A state command (its clears become clear records).
  void state(size_t item, const Command& cmd, const RasterState& st);
  // The end-of-frame item: the last render pass, then the end-of-frame marker.
  void end_of_frame(size_t item);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The binner and the tile buffer's memory at run time.
class TbBinner {
 public:
  using Mismatch = std::function<void(const std::string&)>;
  using ReadWord = std::function<uint32_t(uint32_t addr, uint64_t t)>;
  using WriteWord = std::function<void(uint32_t addr, uint32_t data, uint64_t t)>;
  TbBinner(const TbSetup& s, MemorySystem* mem, Mismatch mismatch, ReadWord read, WriteWord write);

  bool done() const { return pc_ >= ops_.size() && responses_.empty() && beats_left_ == 0 && !store_pending_; }
  // Before the clock falls: the item offered to rast_top's triangle port (null: none; the
  // RTL's triangle FIFO and setup FIFO hold it back when full: fifo.triangle_depth + 1
  // items more ahead of coarse raster than the timed model's fifos.bin_fifo).
  const TbItem* feed(uint64_t t) const;
  // After: assembly offers `item` (or nothing); true when the binner takes it.
  bool take(uint64_t t, const TbItem* offered, size_t item);
  // After: the fed item taken or not; markers taken are appended to `markers`.
  void advance(uint64_t t, bool fed, std::deque<size_t>& markers);
  // The ROP took bin marker `m`'s command at t.
  void command(uint64_t t, const TbBinMarker& m);
  // The tile buffer's port: before the clock falls (ready, a due response), after (its request).
  void drive_port(uint64_t t, RastPorts& ports);
  void serve_port(uint64_t t, RastPorts& ports);

 private:
  struct Response {
    uint64_t due = 0;
    std::vector<uint32_t> words;
  };
  const TbSetup& s_;
  const std::vector<TbBinOp>& ops_;
  MemorySystem* mem_;
  Mismatch mismatch_;
  ReadWord read_;
  WriteWord write_;
  size_t pc_ = 0;
  uint64_t wait_until_ = 0;
  // A store beat taken: its words come with the next cycle's port (rast_tile_buffer.sv).
  bool store_pending_ = false;
  uint32_t store_addr_ = 0;
  int store_count_ = 0;
  // The store in progress resolves colour (marker bit 2): a colour beat's words are pixels
  // of the one-sample layout, each written to every sample (S equal samples resolve to it).
  bool resolving_ = false, store_resolved_ = false;
  // The load or store in progress: beats expected and issued, the load's arrival.
  uint64_t beats_left_ = 0, beats_ = 0, beat_ = 0, arrival_ = 0;
  bool loading_ = false;
  std::deque<Response> responses_;
};

}  // namespace rastsim::rtlsim
