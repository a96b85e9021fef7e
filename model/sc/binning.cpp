// SPDX-License-Identifier: Apache-2.0
#include "sc/binning.h"

#include <algorithm>

#include "ref/pipeline.h"
#include "sc/model_error.h"

namespace rastsim::sc {

namespace {
// A marker's location: no scene line is negative.
constexpr int kBinMarkerLine = -1;
const char* const kBinMarkerFile = "bin marker";
}  // namespace

const BinMarker* bin_marker(const Command& c) {
  if (c.loc.line != kBinMarkerLine || c.loc.file != kBinMarkerFile) return nullptr;
  return static_cast<const BinMarker*>(&c);
}

uint64_t BinRop::command(const Command& cmd, Framebuffer& fb, uint64_t now) {
  if (ctx_.is_end_of_frame(&cmd)) {  // the bins are resolved: the image, no pass
    if (fb.samples > 1) fb = fb.resolve();
    ctx_.resolve_cycles = resolve_cycles_;
    return TimingParams::state_pass_cycles();
  }
  const BinMarker* m = bin_marker(cmd);
  if (!m) throw ModelError("ROP: " + cmd.loc.str() + ": a state command reached the ROP in binned mode (the binner keeps them)");
  const uint64_t pixels = uint64_t(m->rect.area());
  switch (m->kind) {
    case BinMarker::Kind::Begin: {
      uint64_t cycles = port_cycles(m->bytes.total());
      if (mem_ && !m->transfers.empty()) {
        for (const MemoryTransfer& t : m->transfers) mem_->issue_read(MemClient::TileStore, t.address, t.bytes, now);
        if (const auto arrived = mem_->wait_reads(); arrived && *arrived > now) cycles = std::max(cycles, *arrived - now);
      }
      return std::max<uint64_t>(1, cycles);
    }
    case BinMarker::Kind::Clear:
      clear_bin_rect(fb, m->rect, m->clear);
      return p_.rop_clear_cycles(pixels);
    case BinMarker::Kind::End: {
      const uint64_t resolve = m->final_pass && fb.samples > 1 ? p_.resolve_cycles(pixels, fb.samples) : 0;
      resolve_cycles_ += resolve;
      const uint64_t cycles = resolve ? resolve + port_cycles(m->bytes.depth) : port_cycles(m->bytes.total());
      if (mem_)
        for (const MemoryTransfer& t : m->transfers) mem_->post_write(MemClient::TileStore, t.address, t.bytes, now);
      return std::max<uint64_t>(1, cycles);
    }
  }
  return 1;
}

BinnerStage::BinnerStage(SimContext& ctx, const RasterState& arch, const TimingParams& p, const MemoryParams* memory,
                         Link<SetupItem>& in, Link<SetupItem>& out)
    : Stage("binner", ctx, kStallStream), st_(arch), p_(p), in_(in), out_(out), rop_(ctx, p) {
  if (memory)
    bin_mem_.emplace(*memory, arch.fb_width, arch.fb_height, arch.samples, arch.depth_bits,
                     arch.bin.parameter_buffer_base, arch.bin.parameter_buffer_bytes);
  const auto draw = [this](const SetupTriangle& tri, const SetupTriangle&) {
    steps_.push_back({false, uint32_t(&tri - binner_->held().data()), {}});
  };
  binner_.emplace(arch, traversal_params(arch), no_fb_, draw, ctx.render.bin, bin_mem_ ? &*bin_mem_ : nullptr);
  Binner::Hooks h;
  h.begin_bin = [this](int, const PixelRect& r, BinBytes load) { begin_bin(r, load); };
  h.clear = [this](const BinClear& c, const PixelRect&) { steps_.push_back({true, 0, c}); };
  h.end_bin = [this](int, const PixelRect& r, bool final_pass, BinBytes store) { play_bin(r, final_pass, store); };
  binner_->set_hooks(std::move(h));
}

void BinnerStage::attach_memory(MemorySystem& mem) {
  if (!bin_mem_) throw ModelError("binner: a memory system without memory parameters");
  mem_ = &mem;
  rop_.attach_memory(mem);
  // Parameter-buffer writes are posted now; reads wait for the bin's start; tile loads
  // and stores travel with the bin's markers to the ROP.
  bin_mem_->on_transfer = [this](BinMemory::Client c, const MemoryTransfer& t) {
    if (c == BinMemory::Client::TileStore) tile_.push_back(t);
    else if (t.write) mem_->post_write(MemClient::Binning, t.address, t.bytes, now());
    else reads_.push_back(t);
  };
}

MemoryStats BinnerStage::memory_stats() const {
  MemoryStats m;
  if (!bin_mem_) return m;
  m.enabled = m.binned = true;
  m.binning = bin_mem_->binning_stats();
  m.tile_store = bin_mem_->tile_store_stats();
  return m;
}

// A Binner call that may render a pass (an overflow): the pass used held_ as it was and
// emptied the Binner's triangles, so held_ empties too.
template <class F>
void BinnerStage::binner_call(F&& f) {
  const uint64_t overflows = ctx_.render.bin.bin_overflows;
  f();
  if (ctx_.render.bin.bin_overflows != overflows) held_.clear();
}

void BinnerStage::body() {
  for (;;) {
    SetupItem in = read(in_);
    if (in.state) {
      state(in.state);
      continue;
    }
    if (commands_.empty()) throw ModelError("binner: a triangle without its command (setup's log is empty)");
    const CommandPtr cmd = std::move(commands_.front());
    commands_.pop_front();
    const uint64_t candidates = uint64_t(binner_->bin_range(in.work->bbox).area());
    binner_call([&] { binner_->add_triangle(*in.work, cmd->loc); });
    // Recorded (listed in a bin): a copy of its own, held for the pass, so setup's pool
    // (sc/recycler.h, which expects few triangles in flight) gets its triangle back.
    if (binner_->held().size() > held_.size()) held_.push_back(make_local<SetupTriangle>(*in.work));
    attribute_to_no_tile();
    busy(binning_triangle_cycles(candidates));
  }
}

// A state command: clears become clear records, the end of frame renders the last pass
// and goes on to the ROP; viewport and scissor stop here (setup applied them).
void BinnerStage::state(const CommandPtr& cmd) {
  attribute_to_no_tile();
  busy(TimingParams::state_pass_cycles());
  if (ctx_.is_end_of_frame(cmd)) {
    binner_call([&] { binner_->finish(); });
    held_.clear();
    busy(TimingParams::state_pass_cycles());
    write(out_, SetupItem{cmd, nullptr});
    return;
  }
  if (const auto* c = std::get_if<CmdClear>(&cmd->body))
    binner_call([&] { binner_->add_clear_color(c->r, c->g, c->b, cmd->loc); });
  else if (const auto* d = std::get_if<CmdClearDepth>(&cmd->body))
    binner_call([&] { binner_->add_clear_depth(clear_depth_value(*d, cmd->loc, st_), cmd->loc); });
}

void BinnerStage::begin_bin(const PixelRect& r, BinBytes load) {
  rect_ = r;
  load_ = load;
  steps_.clear();
  reads_.clear();
  tile_.clear();
}

void BinnerStage::send(LocalPtr<BinMarker> m) {
  m->loc = SourceLoc{kBinMarkerFile, kBinMarkerLine};
  m->body = CmdScissor{};
  busy(TimingParams::state_pass_cycles());
  write(out_, SetupItem{CommandPtr(std::move(m)), nullptr});
}

// One bin's render, timed (sc/binning.h): the list prefetch, the begin marker with the
// loads, the clears and triangles in record order, the end marker with the stores.
void BinnerStage::play_bin(const PixelRect& r, bool final_pass, BinBytes store) {
  if (mem_ && !reads_.empty()) {
    const uint64_t t0 = now();
    for (const MemoryTransfer& t : reads_) mem_->issue_read(MemClient::Binning, t.address, t.bytes, t0);
    if (const auto arrived = mem_->wait_reads(); arrived && *arrived > t0) busy(*arrived - t0);
  }
  const auto split = std::stable_partition(tile_.begin(), tile_.end(), [](const MemoryTransfer& t) { return !t.write; });
  auto begin = make_local<BinMarker>();
  begin->kind = BinMarker::Kind::Begin;
  begin->rect = r;
  begin->bytes = load_;
  begin->transfers.assign(tile_.begin(), split);
  send(std::move(begin));
  for (const Step& s : steps_) {
    if (s.clear) {
      auto c = make_local<BinMarker>();
      c->kind = BinMarker::Kind::Clear;
      c->rect = r;
      c->clear = s.value;
      send(std::move(c));
      continue;
    }
    attribute_to(r.x0, r.y0);
    busy(1);
    write(out_, SetupItem{nullptr, held_.at(s.tri)});
  }
  auto end = make_local<BinMarker>();
  end->kind = BinMarker::Kind::End;
  end->rect = r;
  end->bytes = store;
  end->final_pass = final_pass;
  end->transfers.assign(split, tile_.end());
  send(std::move(end));
  steps_.clear();
  reads_.clear();
  tile_.clear();
}

}  // namespace rastsim::sc
