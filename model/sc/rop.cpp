// SPDX-License-Identifier: Apache-2.0
#include "sc/rop.h"

#include <algorithm>
#include <optional>
#include <span>
#include <string>

#include "ref/pipeline.h"
#include "ref/rop.h"
#include "sc/hiz_flush.h"
#include "sc/hiz_interlock.h"
#include "sc/model_error.h"
#include "timing/memory_timing.h"

namespace rastsim::sc {

namespace {

struct RopBatchCounts {
  uint64_t accesses = 0, passed = 0, samples_passed = 0;
};

// Hi-Z's flush (sc/hiz_flush.h): at each group's response p, the tile's depth writes to
// spilled blocks that group decided (fragment k in group k / group) go to the engine, and
// at the last the batch's end.
struct HizBundles {
  HizFlush& flush;
  const std::vector<HizSpillWrite>& w;
  uint64_t group;
  size_t next = 0;  // the first write not handed over
  uint64_t g = 0;   // the group responding
  void response(uint64_t p, bool last) {
    const size_t b = next;
    while (next < w.size() && (last || w[next].fragment / group <= g)) ++next;
    if (next > b || last) flush.bundle(p, w.data() + b, next - b, last);
    ++g;
  }
};

// Fragment k of the batch at the ROP's depth port: tested and written (rop_write), or,
// culled by early Z (docs/depth-culling.md), only its early test's depth reads made in
// its place in the stream (early_depth_cull, as the reference's). The early test ran on
// a copy of this depth buffer as the ROP has it now, so the fragment must fail here too.
bool rop_fragment(Framebuffer& fb, const FragmentBatch& batch, size_t k, DepthFunc func, bool depth_write,
                  uint64_t* samples_passed, RopMemory* mem) {
  const Fragment& f = batch.storage[k];
  if (!batch.is_culled(k)) return rop_write(fb, f, func, depth_write, samples_passed, mem);
  if (!early_depth_cull(fb, f, func, mem))
    throw ModelError("ROP: a fragment early Z culled at (" + std::to_string(f.x) + ", " + std::to_string(f.y) +
                     ") passes the depth test at the ROP");
  return false;
}

// A batch's fragments through the timed memory system a group at a time (timing/
// memory_timing.h, memory_group_response: `group_accesses` accesses a group, a
// fragment's accesses made by the group of its first one), the first group issued at core
// cycle `start`; returns the cycle the last group's response comes (`start`: no access).
// `func`: the batch's depth function (always in a tile Hi-Z accepted). `hiz`, if given,
// sees each group's response (its depth writes decided then).
uint64_t rop_write_groups(Framebuffer& fb, const FragmentBatch& batch, DepthFunc func, bool depth_write,
                          RopMemoryPort& port, uint64_t group_accesses, uint64_t start, RopBatchCounts& n,
                          HizBundles* hiz) {
  uint64_t issue = start, group_end = group_accesses;
  port.begin(issue);
  const auto respond = [&] {  // the current group's response; the next group issues then
    issue = memory_group_response(issue, port.end());
    if (hiz) hiz->response(issue, false);
    port.begin(issue);
    group_end += group_accesses;
  };
  for (size_t k = 0; k < batch.count; ++k) {
    const Fragment& f = batch.storage[k];
    if (n.accesses == group_end) respond();  // f's first access opens the next group
    n.passed += rop_fragment(fb, batch, k, func, depth_write, &n.samples_passed, &port.functional());
    n.accesses += TimingParams::rop_accesses(f.mask, fb.samples);
    while (n.accesses > group_end) respond();  // f's later accesses fill further groups
  }
  if (!n.accesses) return start;
  issue = memory_group_response(issue, port.end());
  if (hiz) hiz->response(issue, true);
  return issue;
}

// rop_write_groups for a one-sample batch (every fragment one access), a run at a time:
// rop_write_run makes the same accesses as rop_write on each fragment in turn, with the
// storage tile looked up once a run; a run is cut where a group ends.
uint64_t rop_write_group_runs(Framebuffer& fb, const FragmentBatch& batch, DepthFunc func, bool depth_write,
                              RopMemoryPort& port, uint64_t group_accesses, uint64_t start, RopBatchCounts& n,
                              HizBundles* hiz) {
  uint64_t issue = start, in_group = 0;
  port.begin(issue);
  const Fragment* f = batch.fragments().data();
  for (const PixelRun& r : batch.pixels->runs) {
    const auto frag = [f, x0 = r.x0](int x) { return f[x - x0]; };
    for (int x = r.x0; x < r.x1;) {
      if (in_group == group_accesses) {  // the next fragment opens the next group
        issue = memory_group_response(issue, port.end());
        if (hiz) hiz->response(issue, false);
        port.begin(issue);
        in_group = 0;
      }
      const int end = x + int(std::min(uint64_t(r.x1 - x), group_accesses - in_group));
      const uint32_t written = rop_write_run(fb, r.y, x, end, frag, func, depth_write, &port.functional());
      n.passed += written;
      n.samples_passed += written;
      n.accesses += uint64_t(end - x);
      in_group += uint64_t(end - x);
      x = end;
    }
    f += r.x1 - r.x0;
  }
  if (!n.accesses) return start;
  issue = memory_group_response(issue, port.end());
  if (hiz) hiz->response(issue, true);
  return issue;
}

}  // namespace

Rop::Rop(SimContext& ctx, const RasterState& arch, const TimingParams& p,
         Link<FragmentItem>& in, Link<PortGrant>& grant_2d, Link<PortGrant>& done_2d, sc_core::sc_module_name name)
    : Stage(name, ctx, kId), st_(arch), fb_(arch.fb_width, arch.fb_height, arch.samples),
      depth_bytes_(uint64_t((arch.depth_bits + 7) / 8)), p_(p), in_(in), grant_2d_(grant_2d),
      done_2d_(done_2d) {
  // As render_scene: the depth buffer starts at the far value.
  fb_.clear_depth(static_cast<uint32_t>((uint64_t{1} << st_.depth_bits) - 1));
}

void Rop::attach_memory(MemorySystem& mem, const MemoryParams& p, const RopMemory* warm) {
  mem_ = std::make_unique<RopMemoryPort>(mem, p, fb_, st_.depth_bits);
  mem_->begin(0);
  if (warm) return mem_->functional().take_state(*warm);
  mem_->functional().clear_depth();
  mem_->cleared(MemClient::RopDepth);
}

MemoryStats Rop::finish_memory(uint64_t end) {
  if (!mem_) return {};
  if (!frame_finished_) {
    mem_->begin(end);
    mem_->finish();
    mem_->end();
  }
  return mem_->stats();
}

// A command down the triangle path: a 2D command's marker, the end-of-frame marker or a
// state command (sc/rop.h for the cycles and bytes of each).
void Rop::command(const CommandPtr& cmd) {
  if (bins_) {  // binned: a bin marker or the end of frame (sc/binning.h)
    attribute_to_no_tile();
    busy(bins_->command(*cmd, fb_, now()));
    return;
  }
  const uint64_t fb_pixels = uint64_t(fb_.width) * uint64_t(fb_.height);
  if (mem_) mem_->begin(now());
  if (ctx_.is_end_of_frame(cmd)) {  // the multisample resolve pass
    if (mem_) mem_->finish();  // reads the samples: before the framebuffer is resolved
    frame_finished_ = mem_ != nullptr;
    fb_ = fb_.resolve();
    ctx_.resolve_cycles = p_.resolve_cycles(fb_pixels, st_.samples);
    ctx_.framebuffer_bytes += ctx_.render.resolve_bytes;
    attribute_to_no_tile();
    busy(transaction_cycles(ctx_.resolve_cycles));
    return;
  }
  // `clear_bytes`: bytes a pixel the command writes over the whole buffer (0: no clear).
  // A clear's writes enter the memory at the command's first cycle, before its busy: in
  // lock-step the busy waits for SystemC time to pass, and a request made after that
  // would enter behind the other clients' later ones (sc/sim_context.h, memory_time_order).
  const auto state = [&](uint64_t clear_bytes, std::optional<MemClient> cleared = std::nullopt) {
    apply_state_command(*cmd, st_, fb_, functional_memory());
    if (mem_ && cleared) mem_->cleared(*cleared);
    ctx_.framebuffer_bytes += fb_pixels * clear_bytes;
    attribute_to_no_tile();
    busy(p_.rop_state_cycles(clear_bytes != 0, fb_pixels));
  };
  visit_command(*cmd, Overloaded{
      [&](const CmdViewport&) { state(0); },
      [&](const CmdScissor&) { state(0); },
      [&](const CmdClear&) { state(4, MemClient::RopColor); },
      [&](const CmdClearDepth&) { state(depth_bytes_, MemClient::RopDepth); },
      [&](const CmdPrimitives&) {
        throw ModelError("ROP: a primitives command as a state item (fetch sends its triangles)");
      },
      [&](const CmdDraw2d&) {
        write(grant_2d_, PortGrant{cmd});
        read(done_2d_, false);  // the same transaction: the marker's, starved while the engine works
        attribute_to_no_tile();
        busy(TimingParams::rop_draw2d_marker_cycles());
      },
  });
}

void Rop::body() {
  for (;;) {
    const FragmentItem in = read(in_);
    if (in.state) {
      // Hi-Z's interlock (sc/hiz_interlock.h): a state item ends as the ROP takes it, in its
      // first cycle (a depth clear sets the table then; its writes follow, in order),
      // recorded before its busy: in lock-step the busy waits for SystemC time to pass, and
      // coarse raster, woken by a later record, would go on behind SystemC time.
      const uint64_t taken = now() + 1;
      if (ctx_.on_rop_state && !bins_ && !ctx_.is_end_of_frame(in.state)) ctx_.on_rop_state(*in.state, now());
      if (ctx_.hiz_interlock) ctx_.hiz_interlock->rop_end(taken);
      command(in.state);
      // Early Z's (sc/interpolate.h): the early test reads the depth surface, so a depth
      // clear ends at its last write (the end of its busy), anything else at its take.
      if (ctx_.early_interlock)
        ctx_.early_interlock->rop_end(std::holds_alternative<CmdClearDepth>(in.state->body) ? now() : taken);
      continue;
    }
    const FragmentBatch& batch = *in.work;
    const std::span<const Fragment> frags = batch.fragments();
    // A tile Hi-Z accepted is tested with `always`: every fragment passes, no depth read
    // (as the reference's ROP, docs/depth-culling.md).
    const DepthFunc func = batch.pixels->hiz_accepted ? DepthFunc::Always : st_.depth_func;
    uint64_t accesses = 0, passed = 0, samples_passed = 0;  // summed locally, added once a batch
    uint64_t cycles = 0;
    // A run at a time where every fragment is one access and none was culled early.
    const bool runs = batch.one_per_pixel() && fb_.samples == 1 && batch.culled_count == 0;
    if (mem_) {
      RopBatchCounts n;
      const uint64_t G = p_.rop_pixels_per_cycle;
      // Hi-Z's spilled blocks this tile writes: their flush from its groups' responses.
      std::optional<HizBundles> hiz;
      if (ctx_.hiz_flush && batch.pixels->hiz_writes) hiz.emplace(HizBundles{*ctx_.hiz_flush, *batch.pixels->hiz_writes, G});
      HizBundles* h = hiz ? &*hiz : nullptr;
      cycles = (runs ? rop_write_group_runs(fb_, batch, func, st_.depth_write, *mem_, G, now(), n, h)
                     : rop_write_groups(fb_, batch, func, st_.depth_write, *mem_, G, now(), n, h)) -
               now();
      accesses = n.accesses;
      passed = n.passed;
      samples_passed = n.samples_passed;
    } else if (runs) {
      // A run at a time: the same tests and writes as rop_write on each fragment in turn
      // (ref/rop.h), the storage tile looked up once a run. Each fragment is one access
      // and, written, one sample.
      const Fragment* f = frags.data();
      for (const PixelRun& r : batch.pixels->runs) {
        const uint32_t n = rop_write_run(
            fb_, r.y, r.x0, r.x1, [f, x0 = r.x0](int x) { return f[x - x0]; }, func, st_.depth_write);
        f += r.x1 - r.x0;
        passed += n;
        samples_passed += n;
      }
      accesses = uint64_t(frags.size()) * TimingParams::rop_accesses(1u, 1);
    } else {
      for (size_t k = 0; k < frags.size(); ++k) {
        accesses += TimingParams::rop_accesses(frags[k].mask, fb_.samples);
        passed += rop_fragment(fb_, batch, k, func, st_.depth_write, &samples_passed, nullptr);
      }
    }
    if (!mem_) cycles = p_.rop_fragment_cycles(accesses);
    ctx_.render.fragments_passed += passed;
    ctx_.render.samples_passed += samples_passed;
    if (st_.depth_write) ctx_.render.depth_writes += samples_passed;  // as ref/pipeline.cpp's count_written
    ctx_.rop_accesses += accesses;
    ctx_.framebuffer_bytes += accesses * (4 + depth_bytes_);
    if (!frags.empty()) attribute_to(frags.front().x, frags.front().y);  // the batch's tile
    busy(cycles);
    // Hi-Z's interlock: the batch ends when its last group's depth writes are decided, on
    // that group's read data, in the cycle after its busy (the busy runs up to the
    // response's cycle, which rast_rop does not count when the write is taken in it).
    if (ctx_.hiz_interlock) ctx_.hiz_interlock->rop_end(now() + 1);
    if (ctx_.early_interlock) ctx_.early_interlock->rop_end(now() + 1);  // early Z's, the same end
  }
}

}  // namespace rastsim::sc
