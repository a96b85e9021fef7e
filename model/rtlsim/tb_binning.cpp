// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/tb_binning.h"

#include <algorithm>
#include <optional>

#include "ref/binning.h"
#include "ref/coarse_raster.h"
#include "ref/interpolate.h"
#include "ref/memory/bin_memory.h"
#include "ref/pipeline.h"
#include "ref/traverse.h"
#include "rtlsim/testbench.h"

namespace rastsim::rtlsim {

uint64_t tile_beats(const int rect[4], uint32_t flags, int samples, int depth_bits, int port_bytes) {
  const uint64_t w = uint64_t(rect[2] - rect[0]), h = uint64_t(rect[3] - rect[1]);
  const uint64_t row = w * uint64_t(samples);  // samples a row
  const auto beats = [&](uint64_t words, uint64_t per_beat) { return h * ((words + per_beat - 1) / per_beat); };
  uint64_t n = 0;
  if (flags & 1) n += beats(flags & 4 ? w : row, uint64_t(port_bytes) / 4);
  if (flags & 2) n += beats(row, uint64_t(port_bytes) / bin_depth_sample_bytes(depth_bits));
  return n;
}

// ---- Set-up: the program ----

struct BinProgram::Impl {
  Impl(TbSetup& s, int tile_size);
  void draw(const SetupTriangle& tri, const SetupTriangle& walk);
  void begin_bin(const PixelRect& r, BinBytes load);
  void clear(const BinClear& c);
  void end_bin(const PixelRect& r, bool final_pass, BinBytes store);
  size_t marker(TbBinMarker m);
  template <class F>
  void call(F&& f);

  TbSetup& s;
  const int tile_size;
  Framebuffer no_fb{1, 1};  // the Binner's, never written (the clear hook is set)
  BinStats stats;
  std::optional<BinMemory> mem;
  std::optional<Binner> binner;
  std::vector<size_t> held;  // Binner::held()'s stream items
  TraversalCounters counters;
  // The bin being rendered: its rectangle, its prefetch op and begin marker, transfers.
  PixelRect rect;
  size_t prefetch_op = 0, begin_marker = 0;
  std::vector<MemoryTransfer> writes, reads, tile;
};

BinProgram::Impl::Impl(TbSetup& setup, int tile_px) : s(setup), tile_size(tile_px) {
  const RasterState& st = s.arch;
  if (s.memory.enabled) {
    mem.emplace(s.memory, st.fb_width, st.fb_height, st.samples, st.depth_bits, st.bin.parameter_buffer_base,
                st.bin.parameter_buffer_bytes);
    mem->on_transfer = [this](BinMemory::Client c, const MemoryTransfer& t) {
      if (c == BinMemory::Client::TileStore) tile.push_back(t);
      else (t.write ? writes : reads).push_back(t);
    };
  }
  binner.emplace(st, traversal_params(st), no_fb, [this](const SetupTriangle& tri, const SetupTriangle& walk) {
    draw(tri, walk);
  }, stats, mem ? &*mem : nullptr);
  Binner::Hooks h;
  h.begin_bin = [this](int, const PixelRect& r, BinBytes load) { begin_bin(r, load); };
  h.clear = [this](const BinClear& c, const PixelRect&) { clear(c); };
  h.end_bin = [this](int, const PixelRect& r, bool final_pass, BinBytes store) { end_bin(r, final_pass, store); };
  binner->set_hooks(std::move(h));
}

size_t BinProgram::Impl::marker(TbBinMarker m) {
  m.rect[0] = rect.x0;
  m.rect[1] = rect.y0;
  m.rect[2] = rect.x1;
  m.rect[3] = rect.y1;
  s.binning.markers.push_back(std::move(m));
  TbItem it;
  it.kind = TbItem::Marker;
  it.fed = true;
  it.bin_marker = int(s.binning.markers.size() - 1);
  s.items.push_back(it);
  s.binning.ops.push_back(TbBinOp{TbBinOp::Feed, s.items.size() - 1, 1, {}});
  return s.binning.markers.size() - 1;
}

void BinProgram::Impl::begin_bin(const PixelRect& r, BinBytes load) {
  rect = r;
  reads.clear();
  tile.clear();
  prefetch_op = s.binning.ops.size();
  s.binning.ops.push_back(TbBinOp{TbBinOp::Prefetch, 0, 0, {}});
  TbBinMarker m;
  m.op = 4;
  m.value = (load.color ? 1u : 0u) | (load.depth ? 2u : 0u);
  begin_marker = marker(std::move(m));
}

void BinProgram::Impl::clear(const BinClear& c) {
  TbBinMarker m;
  m.op = c.depth ? 2 : 1;
  m.value = c.depth ? c.z : uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | 0xffu << 24;
  marker(std::move(m));
}

// A listed triangle: fed with its clip rectangle clipped to the bin (rast_tri_setup's box
// is then the reference's walk), its fragments the reference's draw(tri, walk).
void BinProgram::Impl::draw(const SetupTriangle& tri, const SetupTriangle& walk) {
  const size_t index = size_t(&tri - binner->held().data());
  TbItem it = s.items.at(held.at(index));
  it.fed = true;
  it.clip[0] = std::max(it.clip[0], rect.x0);
  it.clip[1] = std::max(it.clip[1], rect.y0);
  it.clip[2] = std::min(it.clip[2], rect.x1);
  it.clip[3] = std::min(it.clip[3], rect.y1);
  s.items.push_back(it);
  s.binning.ops.push_back(TbBinOp{TbBinOp::Feed, s.items.size() - 1, 1, {}});
  const int F = s.arch.coord_format.frac_bits;
  traverse_triangle(walk, tile_size, F, counters, [&](int px, int py, uint32_t m) {
    shade_pixel(tri, px, py, m, F, [&](const Fragment& f) { s.expected.push_back(Expected{f, it.tri}); });
  });
}

void BinProgram::Impl::end_bin(const PixelRect& r, bool final_pass, BinBytes store) {
  const auto split = std::stable_partition(tile.begin(), tile.end(), [](const MemoryTransfer& t) { return !t.write; });
  s.binning.ops[prefetch_op].transfers = reads;
  TbBinMarker& b = s.binning.markers[begin_marker];
  b.transfers.assign(tile.begin(), split);
  b.beats = tile_beats(b.rect, b.value, s.arch.samples, s.arch.depth_bits, s.params.tile_port_bytes);
  TbBinMarker m;
  m.op = 5;
  m.value = 1u | (store.depth ? 2u : 0u) | (final_pass && s.arch.samples > 1 ? 4u : 0u);
  m.transfers.assign(split, tile.end());
  rect = r;
  const size_t e = marker(std::move(m));
  TbBinMarker& em = s.binning.markers[e];
  em.beats = tile_beats(em.rect, em.value, s.arch.samples, s.arch.depth_bits, s.params.tile_port_bytes);
}

// A Binner call that may render an overflow pass: the pass drew from `held` as it was and
// emptied the Binner's triangles (sc/binning.cpp binner_call).
template <class F>
void BinProgram::Impl::call(F&& f) {
  const uint64_t overflows = stats.bin_overflows;
  f();
  if (stats.bin_overflows != overflows) held.clear();
}

BinProgram::BinProgram(TbSetup& s, int tile_size) : impl_(std::make_unique<Impl>(s, tile_size)) {}
BinProgram::~BinProgram() = default;

void BinProgram::triangle(size_t item, const SetupTriangle* tri, const SourceLoc& loc) {
  Impl& m = *impl_;
  const size_t at = m.s.binning.ops.size();  // the take goes before an overflow pass it causes
  const uint64_t setup = m.s.timing.setup_triangle_cycles();
  uint64_t cycles = setup;
  if (tri) {
    cycles = std::max(setup, uint64_t(std::max<int64_t>(1, m.binner->bin_range(tri->bbox).area())));
    m.writes.clear();
    m.call([&] { m.binner->add_triangle(*tri, loc); });
    if (m.binner->held().size() > m.held.size()) m.held.push_back(item);
  }
  m.s.binning.ops.insert(m.s.binning.ops.begin() + std::ptrdiff_t(at), TbBinOp{TbBinOp::Take, item, cycles, m.writes});
  m.writes.clear();
}

void BinProgram::state(size_t item, const Command& cmd, const RasterState& st) {
  Impl& m = *impl_;
  const size_t at = m.s.binning.ops.size();
  m.writes.clear();
  if (const auto* c = std::get_if<CmdClear>(&cmd.body))
    m.call([&] { m.binner->add_clear_color(c->r, c->g, c->b, cmd.loc); });
  else if (const auto* d = std::get_if<CmdClearDepth>(&cmd.body))
    m.call([&] { m.binner->add_clear_depth(clear_depth_value(*d, cmd.loc, st), cmd.loc); });
  m.s.binning.ops.insert(m.s.binning.ops.begin() + std::ptrdiff_t(at), TbBinOp{TbBinOp::Take, item, 1, m.writes});
  m.writes.clear();
}

void BinProgram::end_of_frame(size_t item) {
  Impl& m = *impl_;
  m.s.binning.ops.push_back(TbBinOp{TbBinOp::Take, item, 1, {}});
  m.call([&] { m.binner->finish(); });
  m.held.clear();
  m.rect = {};
  TbBinMarker eof;  // op 0: a pass
  m.marker(std::move(eof));
  if (m.mem) {
    m.s.binning.memory.enabled = m.s.binning.memory.binned = true;
    m.s.binning.memory.binning = m.mem->binning_stats();
    m.s.binning.memory.tile_store = m.mem->tile_store_stats();
  }
}

// ---- Run time ----

TbBinner::TbBinner(const TbSetup& s, MemorySystem* mem, Mismatch mismatch, ReadWord read, WriteWord write)
    : s_(s), ops_(s.binning.ops), mem_(mem), mismatch_(std::move(mismatch)), read_(std::move(read)),
      write_(std::move(write)) {}

const TbItem* TbBinner::feed(uint64_t t) const {
  if (pc_ >= ops_.size() || t < wait_until_ || ops_[pc_].kind != TbBinOp::Feed) return nullptr;
  return &s_.items[ops_[pc_].item];
}

bool TbBinner::take(uint64_t t, const TbItem* offered, size_t item) {
  if (!offered || pc_ >= ops_.size() || t < wait_until_ || ops_[pc_].kind != TbBinOp::Take) return false;
  const TbBinOp& op = ops_[pc_];
  if (op.item != item) {
    mismatch_("cycle " + std::to_string(t) + ": the binner expected stream item " + std::to_string(op.item) +
              ", assembly offers " + std::to_string(item));
    return false;
  }
  if (mem_)
    for (const MemoryTransfer& w : op.transfers) mem_->post_write(MemClient::Binning, w.address, w.bytes, t);
  wait_until_ = t + op.cycles;
  ++pc_;
  return true;
}

// The fed item's handshake, then the steps that need no partner: a bin's list prefetch
// (its reads issued now, the binner waiting for the last).
void TbBinner::advance(uint64_t t, bool fed, std::deque<size_t>& markers) {
  if (fed) {
    const size_t item = ops_[pc_].item;
    if (s_.items[item].kind == TbItem::Marker) markers.push_back(item);
    wait_until_ = t + 1;
    ++pc_;
  }
  while (pc_ < ops_.size() && ops_[pc_].kind == TbBinOp::Prefetch && t + 1 >= wait_until_) {
    const uint64_t t0 = std::max(t + 1, wait_until_);
    uint64_t until = t0;
    if (mem_ && !ops_[pc_].transfers.empty()) {
      for (const MemoryTransfer& r : ops_[pc_].transfers) mem_->issue_read(MemClient::Binning, r.address, r.bytes, t0);
      if (const auto a = mem_->wait_reads(); a && *a > t0) until = *a;
    }
    wait_until_ = until;
    ++pc_;
  }
}

void TbBinner::command(uint64_t t, const TbBinMarker& m) {
  if (m.op != 4 && m.op != 5) return;
  if (beats_left_ != 0 || !responses_.empty())
    mismatch_("cycle " + std::to_string(t) + ": a bin command while the tile buffer's last load or store runs");
  loading_ = m.op == 4;
  resolving_ = m.op == 5 && (m.value & 4u) != 0;
  beats_left_ = beats_ = m.beats;
  beat_ = 0;
  arrival_ = t + 1;
  if (!mem_) return;
  if (loading_) {
    for (const MemoryTransfer& r : m.transfers) mem_->issue_read(MemClient::TileStore, r.address, r.bytes, t);
    if (const auto a = mem_->wait_reads(); a && *a > arrival_) arrival_ = *a;
  } else {
    for (const MemoryTransfer& w : m.transfers) mem_->post_write(MemClient::TileStore, w.address, w.bytes, t);
  }
}

void TbBinner::drive_port(uint64_t t, RastPorts& ports) {
  const bool respond = !responses_.empty() && responses_.front().due <= t;
  ports.drive_tile(true, respond, respond ? responses_.front().words : std::vector<uint32_t>{});
  if (respond) responses_.pop_front();
}

// A beat taken: a store's words into the memory; a load's read now, answered in order
// (beat k of n at max(its issue + 1, arrival - (n - 1 - k))).
void TbBinner::serve_port(uint64_t t, RastPorts& ports) {
  const TileBeat b = ports.tile_beat();
  if (store_pending_) {  // the words of the store beat taken in the cycle before
    const uint32_t S = store_resolved_ ? uint32_t(s_.samples) : 1;
    for (uint32_t i = 0; i < uint32_t(store_count_); ++i)
      for (uint32_t k = 0; k < S; ++k) write_(((store_addr_ / 4 + i) * S + k) * 4, b.words[size_t(i)], t);
    store_pending_ = false;
  }
  if (!b.valid) return;
  if (beats_left_ == 0 || b.write == loading_) {
    mismatch_("cycle " + std::to_string(t) + ": the tile buffer's " + (b.write ? "store" : "load") +
              " beat at byte " + std::to_string(b.addr) + " was not asked for (or is one too many)");
    return;
  }
  --beats_left_;
  if (b.write) {
    store_pending_ = true;
    store_addr_ = b.addr;
    store_count_ = b.count;
    // A resolved store's colour beats (below the depth surface) hold pixels.
    store_resolved_ = resolving_ && b.addr < rop_depth_base(s_.arch.fb_width, s_.arch.fb_height, s_.samples);
    ++beat_;
    return;
  }
  Response r;
  r.words.assign(size_t(s_.params.tile_port_words), 0);
  for (int i = 0; i < b.count; ++i) r.words[size_t(i)] = read_(b.addr + 4 * uint32_t(i), t);
  const uint64_t back = beats_ - 1 - beat_;
  r.due = std::max(t + 1, arrival_ > back ? arrival_ - back : 0);
  if (!responses_.empty()) r.due = std::max(r.due, responses_.back().due + 1);
  responses_.push_back(std::move(r));
  ++beat_;
}

}  // namespace rastsim::rtlsim
