// SPDX-License-Identifier: Apache-2.0
// The cycle loop of the co-simulation, one template instance per verilated config
// (Vrast_<config>, generated registry rtl_registry.cpp). Used by cosim.cpp and the
// registry only; callers use cosim.h.
//
// Timing convention (the same as the RTL's and, shifted by nothing, the SystemC
// model's): a stage that takes an item in cycle u and needs n cycles offers its result
// in cycle u + n - 1; a FIFO entry pushed in cycle v is visible in cycle v + 1 (SystemC
// time v + 1); a push into a full FIFO succeeds when the reader pops in the same cycle.
// The testbench stages below follow model/sc/command_fetch.cpp, prim_assembly.cpp and
// rop.cpp exactly, with the cost equations of TimingParams; the cycle count is the
// ROP's last busy cycle + 1, as the model's.
//
// Stage statistics (docs/microarchitecture.md "Stage statistics"): every cycle each
// stage is busy, stalled or starved, as the SystemC Stage accounts it. The testbench
// stages (and the 2D front end and engine) count their own cycles; setup, coarse raster,
// fine raster and interpolation are classified from rast_top's dbg_has_o / dbg_done_o /
// dbg_blocked_o handshake ports.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstring>
#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vrast_engine2d.h"

#include "config/timing_params.h"
#include "rtl/cosim.h"
#include "ref/interpolate.h"
#include "ref/pipeline.h"
#include "ref/rop.h"
#include "ref/sample_pattern.h"

namespace rastsim::cosim {

// One transaction of the testbench's command stream.
struct TbItem {
  enum Kind { Triangle, Marker, Null } kind = Triangle;
  uint64_t fetch_cost = 1;     // command fetch cycles (header + vertices)
  uint64_t assembly_cost = 1;  // primitive assembly cycles (1 for a marker)
  uint64_t rop_cost = 1;       // markers: ROP cycles (a clear's fast-clear time, else 1)
  int64_t x[3] = {}, y[3] = {};  // snapped raw coordinates
  uint32_t z[3] = {};
  uint32_t rgb[3] = {};        // {b, g, r} packed as the RTL port
  int clip[4] = {};            // x0, y0, x1, y1
  int origin[2] = {};          // x, y
  int tri = -1;                // triangle index (names in TbSetup::tri_names)
  const Command* cmd = nullptr;  // markers: the state or 2D command (none: the end-of-frame marker)
  int work2d = -1;             // 2D markers: index in TbSetup::work2d
};
// A 2D command's engine operations (ref/2d/draw2d.h) and its front-end cost.
struct TbWork2d {
  Draw2dWork work;
  uint64_t setup_cost = 1;     // 2D front end cycles (TimingParams::setup2d_cycles)
  std::string name;            // "file:line"
};

struct Expected {
  Fragment f;
  int tri = 0;
};

struct TbSetup {
  RtlParams params;                     // of the verilated model (widths, timing)
  // Run-time raster state of the config being simulated, driven on rast_top's static
  // inputs: log2 tile size, fill rule, cull mode (raster_state.h's enum values), front face.
  int tile_log2 = 0;
  int fill_rule = 0, cull_mode = 0, front_ccw = 1;
  // Multisampling: raster.samples and its snapped offsets (ref/sample_pattern.h), raw,
  // driven on samples_log2_i / sample_dx_i / sample_dy_i.
  int samples = 1;
  std::array<int64_t, kMaxSamples> sample_dx{}, sample_dy{};
  std::vector<TbItem> items;
  std::vector<Expected> expected;
  std::vector<std::string> tri_names;   // "file:line triangle k"
  std::vector<TbWork2d> work2d;         // the 2D commands, in order
  RasterState arch;                     // the config's state: the testbench ROP applies state commands to it
  Framebuffer reference;                // the reference model's image of the scene
  TimingParams timing;                  // of the config being simulated: FIFO depths, ROP cost
  CosimOptions opts;
};

using RunFn = void (*)(const TbSetup&, CosimResult&);
struct RegistryEntry {
  const char* name;    // the config's name, or <config>_circuit (the divider as its circuit)
  const char* config;  // configs/<config>.toml
  RunFn run;
  RtlParams params;  // what Vrast_<name> was built with
};
const std::vector<RegistryEntry>& rtl_registry();  // generated: rtl_registry.cpp

// Bits [lsb, lsb + w) of a verilated port (C integer or VlWide), w <= 64.
template <class T>
uint64_t port_bits(const T& v, int lsb, int w) {
  const uint64_t mask = (w >= 64) ? ~uint64_t{0} : ((uint64_t{1} << w) - 1);
  if constexpr (std::is_integral_v<T>) {
    return (static_cast<uint64_t>(v) >> lsb) & mask;
  } else {
    // A 32-bit word (or the part of one the field covers) at a time: at most 3 words for
    // w <= 64 (the testbench reads every fragment lane's fields this way).
    uint64_t r = 0;
    for (int b = lsb; b < lsb + w;) {
      const int sh = b % 32;
      const int n = std::min(32 - sh, lsb + w - b);  // bits taken from this word, 1..32
      r |= ((static_cast<uint64_t>(v[b / 32]) >> sh) & ((uint64_t{1} << n) - 1)) << (b - lsb);
      b += n;
    }
    return r & mask;
  }
}

// Sets bits [lsb, lsb + w) of a verilated port (C integer or VlWide) to v, w <= 64.
template <class T>
void set_port_bits(T& port, int lsb, int w, uint64_t v) {
  if constexpr (std::is_integral_v<T>) {
    const T mask = static_cast<T>(((w >= 64) ? ~uint64_t{0} : ((uint64_t{1} << w) - 1)) << lsb);
    port = static_cast<T>((port & ~mask) | (static_cast<T>(v << lsb) & mask));
  } else {
    for (int i = 0; i < w; ++i) {
      const int b = lsb + i;
      if ((v >> i) & 1) port[size_t(b / 32)] |= (1u << (b % 32));
      else port[size_t(b / 32)] &= ~(1u << (b % 32));
    }
  }
}

// A testbench stage: takes an item, is busy `cost` cycles, offers its output in the
// last of them and holds it until taken.
struct TbStage {
  bool active = false;
  uint64_t left = 0;   // busy cycles left, including the current one
  size_t item = 0;
  bool offering() const { return active && left == 1; }
};

// The stages of CosimResult::stages, in pipeline order, with the SystemC model's names.
enum TbStageId { kFetch, kAssembly, kSetup, kCoarse, kFine, kInterp, kRop, kDraw2dSetup, kEngine2d, kStageCount };
inline constexpr const char* kStageNames[kStageCount] = {
    "command_fetch", "prim_assembly", "tri_setup", "coarse_raster", "fine_raster",
    "interpolate",   "rop",           "draw2d_setup", "engine2d"};
enum class Cyc : uint8_t { Starved, Busy, Stalled };  // a stage's state in one cycle

// One co-simulation run: the verilated rast_top between the testbench's front end
// (command fetch, command FIFO, primitive assembly) and its back end (fragment
// staging, fragment FIFO, the ROP as a memory model). Each cycle: the back end and
// assembly act on what is visible (ROP, staging, assembly take), the triangle port is
// driven, the clock falls, the fragment port is read, assembly and fetch advance, the
// clock rises.
template <class V>
class RtlBench {
 public:
  RtlBench(const TbSetup& s, CosimResult& r)
      : s_(s), p_(s.params), r_(r), rng_(s.opts.backpressure_seed), stall_(s.opts.backpressure),
        cmd_depth_(size_t(s.timing.fifo_command)), frag_depth_(size_t(s.timing.fragment_fifo_entries())),
        d2_depth_(size_t(s.timing.fifo_draw2d)), op2d_depth_(size_t(s.timing.fifo_op2d)), st_(s.arch),
        fb_(s.arch.fb_width, s.arch.fb_height, s.samples) {
    fb_.clear_depth(static_cast<uint32_t>((uint64_t{1} << st_.depth_bits) - 1));  // as render_scene
  }

  void run() {
    const auto t0 = std::chrono::steady_clock::now();
    r_.stages.assign(kStageCount, StageRecord{});
    for (int k = 0; k < kStageCount; ++k) r_.stages[size_t(k)].name = kStageNames[k];
    open();
    reset();
    uint64_t counted = 0;  // cycles classified (0 .. the last one run)
    for (uint64_t t = 0;; ++t) {
      counted = t + 1;
      if (t >= s_.opts.max_cycles) {
        mismatch("simulation did not finish within " + std::to_string(s_.opts.max_cycles) + " cycles");
        break;
      }
      if (cycle(t)) {
        r_.cycles_rtl = last_busy_ + 1;
        break;
      }
      // Only the ROP left, counting down a long operation (a multisampled frame's resolve
      // pass: up to millions of cycles): skip to its last cycle instead of clocking an
      // idle RTL (the waveform stops here).
      if (rop_left_ > 1 && done_but_rop()) {
        last_busy_ = std::max(last_busy_, t + rop_left_);
        r_.cycles_rtl = last_busy_ + 1;
        // The skipped cycles t + 1 .. t + rop_left_: the ROP busy, every other stage starved.
        for (int k = 0; k < kStageCount; ++k) (k == kRop ? r_.stages[size_t(k)].busy : r_.stages[size_t(k)].starved) += rop_left_;
        counted = t + 1 + rop_left_;
        tx_end(kRop, counted);
        rop_left_ = 0;
        break;
      }
    }
    close_stage_counts(counted);
    end_of_run_check();
    if (fst_) fst_->close();
    top_->final();
    engine_->final();
    r_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

 private:
  // A command-FIFO entry, visible to assembly from the cycle after its push.
  struct Entry {
    size_t item;
    uint64_t pushed;
  };
  // A fragment-FIFO entry: a tile's fragments or a marker, visible to the ROP from the
  // cycle after its push.
  struct Batch {
    uint64_t fragments = 0;
    uint64_t accesses = 0;  // ROP accesses (TimingParams::rop_accesses of each fragment's mask)
    bool marker = false;
    size_t marker_item = 0;
    uint64_t pushed = 0;
    std::vector<Fragment> frags;  // written into the testbench framebuffer by the ROP
  };

  // ---- The model, its waveform and its clock ----
  void open() {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->traceEverOn(!s_.opts.fst_path.empty());
    top_ = std::make_unique<V>(ctx_.get(), "rast_top");
    engine_ = std::make_unique<Vrast_engine2d>(ctx_.get(), "rast_engine2d");
    if (!s_.opts.fst_path.empty()) {
      fst_ = std::make_unique<VerilatedFstC>();
      top_->trace(fst_.get(), 99);
      fst_->open(s_.opts.fst_path.c_str());
    }
  }
  void half(int clk) {
    top_->clk_i = clk;
    top_->eval();
    engine_->clk_i = clk;
    engine_->eval();
    if (fst_) fst_->dump(time_);
    ++time_;
  }
  // Static raster state on its ports, then one reset cycle.
  void reset() {
    top_->tile_log2_i = static_cast<uint8_t>(s_.tile_log2);
    top_->fill_rule_i = static_cast<uint8_t>(s_.fill_rule);
    top_->cull_mode_i = static_cast<uint8_t>(s_.cull_mode);
    top_->front_ccw_i = static_cast<uint8_t>(s_.front_ccw);
    top_->samples_log2_i = static_cast<uint8_t>(std::countr_zero(static_cast<unsigned>(s_.samples)));
    for (int k = 0; k < p_.max_samples; ++k) {
      set_port_bits(top_->sample_dx_i, k * p_.sample_off_w, p_.sample_off_w, uint64_t(s_.sample_dx[size_t(k)]));
      set_port_bits(top_->sample_dy_i, k * p_.sample_off_w, p_.sample_off_w, uint64_t(s_.sample_dy[size_t(k)]));
    }
    top_->tri_valid_i = 0;
    top_->frag_ready_i = 0;
    top_->rst_ni = 0;
    engine_->lanes_i = static_cast<uint8_t>(s_.timing.engine2d_fill_pixels_per_cycle);
    engine_->span_setup_i = static_cast<uint8_t>(s_.timing.engine2d_span_setup);
    engine_->rmw_i = static_cast<uint8_t>(s_.timing.engine2d_rmw);
    engine_->blit_bytes_i = static_cast<uint8_t>(s_.timing.engine2d_blit_bytes_per_cycle);
    engine_->in_valid_i = 0;
    engine_->rst_ni = 0;
    half(0);
    half(1);
    top_->rst_ni = 1;
    engine_->rst_ni = 1;
  }

  // One clock cycle t; true when the run is complete.
  bool cycle(uint64_t t) {
    rop_step(t);
    unblock_staging(t);
    engine_take(t);
    front_end_take(t);
    front_end_step(t);
    const bool op_valid = engine_drive();
    assembly_take(t);
    const bool tri_valid = assembly_.offering();
    drive_triangle(tri_valid);
    const bool frag_ready = !staging_blocked_ && !(s_.opts.backpressure > 0 && stall_(rng_));
    top_->frag_ready_i = frag_ready;
    half(0);
    const bool tri_taken = tri_valid && top_->tri_ready_o;
    observe_rtl_stages(t);
    if (!top_->idle_o || top_->frag_valid_o || fetch_.active || assembly_.active) last_busy_ = std::max(last_busy_, t);
    if (top_->frag_valid_o && frag_ready) take_beat(t);
    engine_memory_and_handshake(t, op_valid);
    assembly_step(t, tri_taken);
    fetch_step(t);
    half(1);
    return done();
  }

  // ---- Back end: the ROP as a memory model (model/sc/rop.cpp) ----
  // Starts the next visible batch when idle and counts its busy cycles.
  void rop_step(uint64_t t) {
    if (rop_wait_2d_) {  // the port is lent to the 2D engine (the SystemC ROP waits in read: starved)
      last_busy_ = t;
      count(kRop, Cyc::Starved);
      return;
    }
    if (rop_left_ == 0 && !frag_fifo_.empty() && frag_fifo_.front().pushed < t) {
      const Batch b = std::move(frag_fifo_.front());
      frag_fifo_.pop_front();
      if (b.marker && s_.items[b.marker_item].work2d >= 0) {
        // One transaction (the model's marker read): the wait for the engine, then the
        // marker's own cycle (engine_done), whose end closes it.
        tx_begin(kRop, t);
        rop_wait_2d_ = true;
        grant_work_ = s_.items[b.marker_item].work2d;
        last_busy_ = t;
        count(kRop, Cyc::Starved);
        return;
      }
      // (The end-of-frame marker has no command: its cost is the resolve pass.)
      if (b.marker && s_.items[b.marker_item].cmd) apply_state_command(*s_.items[b.marker_item].cmd, st_, fb_);
      for (const Fragment& f : b.frags) rop_write(fb_, f, st_.depth_func, st_.depth_write);
      rop_left_ = b.marker ? s_.items[b.marker_item].rop_cost : s_.timing.rop_fragment_cycles(b.accesses);
      if (s_.opts.perturb_rop_cycles && r_.stages[kRop].transactions == s_.opts.perturb_rop_transaction)
        rop_left_ += s_.opts.perturb_rop_cycles;  // test-only (CosimOptions)
      tx_begin(kRop, t);
    }
    if (rop_left_ > 0) {
      --rop_left_;
      last_busy_ = t;
      count(kRop, Cyc::Busy);
      if (rop_left_ == 0) tx_end(kRop, t + 1);
    } else {
      count(kRop, Cyc::Starved);
    }
  }
  // A completed batch pushes into the fragment FIFO, or waits for room there while
  // blocking the interpolator (frag_ready low).
  void push_staging(uint64_t t) {
    if (frag_fifo_.size() < frag_depth_) {
      staging_.pushed = t;
      frag_fifo_.push_back(staging_);
      staging_ = Batch{};
      staging_blocked_ = false;
    } else {
      staging_blocked_ = true;
    }
  }
  void unblock_staging(uint64_t t) {
    if (staging_blocked_) push_staging(t);
  }

  // ---- The 2D path (model/sc/draw2d_setup.cpp, engine2d.cpp) ----
  // The engine takes the next visible operation batch when it has none.
  void engine_take(uint64_t t) {
    engine_worked_ = false;
    if (held_ < 0 && !engine_busy_ && !op2d_fifo_.empty() && op2d_fifo_.front().pushed < t) {
      held_ = int(op2d_fifo_.front().item);
      op2d_fifo_.pop_front();
      tx_begin(kEngine2d, t);  // the model's read of the operation batch
    }
    // The ROP's grant and the held batch: the engine starts (its first cycle takes the port).
    if (rop_wait_2d_ && held_ >= 0 && !engine_busy_) {
      if (held_ != grant_work_) mismatch("2D engine holds " + s_.work2d[size_t(held_)].name + " but the ROP granted " +
                                         s_.work2d[size_t(grant_work_)].name);
      engine_busy_ = true;
      engine_worked_ = true;  // the cycle that takes the port (TimingParams::engine2d_grant_cycles)
      next_op_ = 0;
      if (s_.work2d[size_t(held_)].work.ops.empty()) engine_done(t);
    }
  }
  // The engine's last busy cycle t: its transaction ends (the model's write of done
  // returns at once: the ROP waits for it), the ROP's marker cycle is t + 1.
  void engine_done(uint64_t t) {
    tx_end(kEngine2d, t + 1);
    engine_busy_ = false;
    held_ = -1;
    rop_wait_2d_ = false;
    rop_left_ = 1;  // the ROP's own cycle for the marker, next cycle
  }
  // Drives the next operation and the command's paint state; true when one is offered.
  bool engine_drive() {
    if (!engine_busy_ || next_op_ >= s_.work2d[size_t(held_)].work.ops.size()) {
      engine_->in_valid_i = 0;
      return false;
    }
    const Draw2dWork& w = s_.work2d[size_t(held_)].work;
    const Op2d& op = w.ops[next_op_];
    auto rgb = [](const std::array<uint8_t, 3>& c) { return uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16; };
    const uint32_t mask = (1u << 20) - 1;  // Width = 20 bits of the engine's signed indices
    engine_->rop3_i = w.paint.rop3;
    engine_->fg_i = rgb(w.paint.fg);
    engine_->bg_i = rgb(w.paint.bg);
    uint64_t pat = 0;
    for (int r = 0; r < 8; ++r) pat = pat << 8 | w.paint.pattern.rows[size_t(r)];
    engine_->pattern_i = pat;
    engine_->pattern_solid_i = w.paint.pattern.solid;
    engine_->clip_x0_i = uint32_t(w.clip.x0) & mask;
    engine_->clip_y0_i = uint32_t(w.clip.y0) & mask;
    engine_->clip_x1_i = uint32_t(w.clip.x1) & mask;
    engine_->clip_y1_i = uint32_t(w.clip.y1) & mask;
    engine_->in_valid_i = 1;
    engine_->op_kind_i = uint8_t(op.kind);
    engine_->op_paint_i = uint8_t(op.paint);
    engine_->op_midpoint_i = op.midpoint;
    engine_->op_x0_i = uint32_t(op.x0) & mask;
    engine_->op_y0_i = uint32_t(op.y0) & mask;
    engine_->op_x1_i = uint32_t(op.x1) & mask;
    engine_->op_y1_i = uint32_t(op.y1) & mask;
    engine_->op_sx_i = uint32_t(op.sx) & mask;
    engine_->op_sy_i = uint32_t(op.sy) & mask;
    engine_->op_w_i = uint32_t(op.w) & mask;
    engine_->op_h_i = uint32_t(op.h) & mask;
    return true;
  }
  static int sext20(uint32_t v) { return int(int32_t(v << 12) >> 12); }
  uint32_t fb_rgb(int x, int y) const {
    if (x < 0 || y < 0 || x >= fb_.width || y >= fb_.height) return 0;
    const uint8_t* p = fb_.pixel(x, y);
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16;
  }
  // The framebuffer port (asynchronous read, write at the edge), then the handshake.
  // The engine's cycle is busy from the one that takes the port to the one whose
  // operation completes the command (the testbench offers every operation at once, so
  // the engine never waits: the model's busy(1) + busy(engine2d_op_cycles) per operation);
  // starved otherwise (the model's reads of the operations and of the ROP's grant).
  void engine_memory_and_handshake(uint64_t t, bool op_valid) {
    engine_worked_ = engine_worked_ || engine_busy_;
    count(kEngine2d, engine_worked_ ? Cyc::Busy : Cyc::Starved);
    if (!engine_busy_) return;
    last_busy_ = t;
    const int x = sext20(engine_->mem_x_o), y = sext20(engine_->mem_y_o);
    for (int k = 0; k < 8; ++k) set_lane(k, fb_rgb(x + k, y));
    engine_->mem_s_i = fb_rgb(sext20(engine_->mem_sx_o), sext20(engine_->mem_sy_o));
    engine_->eval();
    if (engine_->mem_we_o) {
      for (int k = 0; k < 8; ++k) {
        if (!((engine_->mem_wmask_o >> k) & 1)) continue;
        if (x + k < 0 || y < 0 || x + k >= fb_.width || y >= fb_.height) {
          mismatch("cycle " + std::to_string(t) + ": the 2D engine wrote outside the framebuffer at (" +
                   std::to_string(x + k) + ", " + std::to_string(y) + ")");
          continue;
        }
        const uint32_t v = uint32_t(port_bits(engine_->mem_wdata_o, k * 24, 24));
        uint8_t* p = fb_.pixel(x + k, y);
        p[0] = uint8_t(v);
        p[1] = uint8_t(v >> 8);
        p[2] = uint8_t(v >> 16);
        p[3] = 255;
        ++r_.pixels_2d;
      }
    }
    const size_t n = s_.work2d[size_t(held_)].work.ops.size();
    const bool all_taken = next_op_ >= n;
    if (op_valid && engine_->in_ready_o) ++next_op_;
    if (all_taken && engine_->in_ready_o) engine_done(t);
  }
  void set_lane(int k, uint32_t v) {
    for (int b = 0; b < 24; ++b) {
      const int bit = k * 24 + b;
      auto& word = engine_->mem_d_i[size_t(bit / 32)];
      if ((v >> b) & 1) word |= (1u << (bit % 32));
      else word &= ~(1u << (bit % 32));
    }
  }
  // The 2D front end: takes a visible command, is busy its cost, pushes its operations.
  void front_end_take(uint64_t t) {
    if (!fe_.active && !d2_fifo_.empty() && d2_fifo_.front().pushed < t) {
      fe_ = TbStage{true, s_.work2d[d2_fifo_.front().item].setup_cost, d2_fifo_.front().item};
      d2_fifo_.pop_front();
      tx_begin(kDraw2dSetup, t);
    }
  }
  // A stage that pushes in its last busy cycle starts its next item the cycle after; one
  // that was blocked on a full FIFO pushes in the cycle the reader pops and starts its
  // next item in that same cycle (the SystemC writer returns from its blocked write then).
  // The cycle is counted as fetch's (fetch_step): busy for a countdown or the first push
  // attempt, stalled for a retried push, and a push after a stall ends that transaction
  // as the cycle starts.
  void front_end_step(uint64_t t) {
    Cyc state = Cyc::Starved;
    for (;;) {
      front_end_take(t);
      if (!fe_.active) break;
      last_busy_ = std::max(last_busy_, t);
      if (fe_.left > 1) {
        --fe_.left;
        state = Cyc::Busy;
        break;
      }
      if (!fe_blocked_) state = Cyc::Busy;
      if (op2d_fifo_.size() >= op2d_depth_) {
        if (fe_blocked_) state = Cyc::Stalled;
        fe_blocked_ = true;
        break;
      }
      op2d_fifo_.push_back(Entry{fe_.item, t});
      fe_.active = false;
      const bool was_blocked = fe_blocked_;
      fe_blocked_ = false;
      tx_end(kDraw2dSetup, was_blocked ? t : t + 1);
      if (!was_blocked) break;
    }
    count(kDraw2dSetup, state);
  }

  // ---- Front end: command fetch and primitive assembly (model/sc/command_fetch.cpp,
  // prim_assembly.cpp) ----
  // Assembly takes a visible command.
  void assembly_take(uint64_t t) {
    if (!assembly_.active && !cmd_fifo_.empty() && cmd_fifo_.front().pushed < t) {
      assembly_ = TbStage{true, s_.items[cmd_fifo_.front().item].assembly_cost, cmd_fifo_.front().item};
      cmd_fifo_.pop_front();
      assembly_offered_ = false;
      tx_begin(kAssembly, t);
    }
  }
  // Assembly counts its busy cycle and hands over on a taken offer. Its last busy cycle
  // offers the triangle; later cycles of the offer are stalled, including the one in
  // which a waited-for offer is taken (the SystemC write returns as that cycle starts).
  void assembly_step(uint64_t t, bool tri_taken) {
    if (!assembly_.active) {
      count(kAssembly, Cyc::Starved);
      return;
    }
    if (assembly_.left > 1) {
      --assembly_.left;
      count(kAssembly, Cyc::Busy);
      return;
    }
    const bool retry = assembly_offered_;
    assembly_offered_ = true;
    count(kAssembly, retry ? Cyc::Stalled : Cyc::Busy);
    if (tri_taken) {
      if (s_.items[assembly_.item].kind == TbItem::Marker) markers_in_flight_.push_back(assembly_.item);
      assembly_.active = false;
      tx_end(kAssembly, retry ? t : t + 1);
    }
  }
  // Fetch starts the scene's next item and pushes it into the command FIFO when done
  // (a 2D command into the 2D front end's FIFO first). Like the front end: after a push
  // that waited for FIFO room, the next item starts in the same cycle.
  // The cycle is busy when fetch works in it (a countdown or the last cycle's first push
  // attempt), stalled when it only retries a blocked push, starved otherwise (a push
  // after a stall ends that transaction as the cycle starts, as the SystemC write returns).
  void fetch_step(uint64_t t) {
    Cyc state = Cyc::Starved;
    for (;;) {
      if (!fetch_.active && next_item_ < s_.items.size()) {
        fetch_ = TbStage{true, s_.items[next_item_].fetch_cost, next_item_++};
        tx_begin(kFetch, t);
      }
      if (!fetch_.active) break;
      last_busy_ = std::max(last_busy_, t);
      if (fetch_.left > 1) {
        --fetch_.left;
        state = Cyc::Busy;
        break;
      }
      if (!fetch_blocked_) state = Cyc::Busy;
      if (s_.items[fetch_.item].kind == TbItem::Null) {
        fetch_.active = false;  // an empty primitive command: header only, nothing out
        tx_end(kFetch, t + 1);
        break;
      }
      const int w2 = s_.items[fetch_.item].work2d;
      if (w2 >= 0 && !fetch_2d_pushed_) {
        if (d2_fifo_.size() >= d2_depth_) {
          if (fetch_blocked_) state = Cyc::Stalled;
          fetch_blocked_ = true;
          break;
        }
        d2_fifo_.push_back(Entry{size_t(w2), t});
        fetch_2d_pushed_ = true;
      }
      if (cmd_fifo_.size() >= cmd_depth_) {
        if (fetch_blocked_) state = Cyc::Stalled;
        fetch_blocked_ = true;
        break;
      }
      cmd_fifo_.push_back(Entry{fetch_.item, t});
      fetch_.active = false;
      fetch_2d_pushed_ = false;
      const bool was_blocked = fetch_blocked_;
      fetch_blocked_ = false;
      tx_end(kFetch, was_blocked ? t : t + 1);
      if (!was_blocked) break;
    }
    count(kFetch, state);
  }

  // ---- Stage statistics ----
  void count(int k, Cyc c) {
    StageRecord& r = r_.stages[size_t(k)];
    ++(c == Cyc::Busy ? r.busy : c == Cyc::Stalled ? r.stalled : r.starved);
  }
  void tx_begin(int k, uint64_t t) {
    meter_[size_t(k)] = Meter{true, t};
    ++r_.stages[size_t(k)].transactions;
  }
  void tx_end(int k, uint64_t t) {
    Meter& m = meter_[size_t(k)];
    if (!m.open) return;
    m.open = false;
    if (s_.opts.record_transactions) r_.stages[size_t(k)].spans.push_back(StageSpan{m.start, t});
  }
  // The RTL stages from rast_top's debug ports (bit 0 setup .. 3 interpolation). No
  // transaction: starved. Setup, coarse and fine raster offer an output in the last
  // cycle of its work (busy, as the SystemC busy(n) before its write), the later cycles
  // of a refused offer are stalled, and so is the cycle in which a waited-for output is
  // finally taken (its work was done before; the SystemC write returns as that cycle
  // starts). The interpolator's refused output freezes its whole pipeline, so each such
  // cycle is stalled, and the cycle it moves again picks pixels (busy).
  void observe_rtl_stages(uint64_t t) {
    for (int s = 0; s < 4; ++s) {
      const int k = kSetup + s;
      const bool has = (top_->dbg_has_o >> s) & 1, done = (top_->dbg_done_o >> s) & 1;
      const bool blocked = has && ((top_->dbg_blocked_o >> s) & 1);
      const bool waited = rtl_blocked_[size_t(s)];  // refused last cycle
      rtl_blocked_[size_t(s)] = blocked;
      const bool stalled = k == kInterp ? blocked : (blocked ? waited : (has && waited));
      const bool handshake_only = has && !blocked && waited && k != kInterp;
      if (has && !meter_[size_t(k)].open) tx_begin(k, t);
      count(k, !has ? Cyc::Starved : stalled ? Cyc::Stalled : Cyc::Busy);
      if (done) tx_end(k, handshake_only ? t : t + 1);
    }
  }
  // The run is cycles_rtl cycles (to the ROP's last busy cycle); the loop may have
  // classified a few more, in which every stage is starved: drop them.
  void close_stage_counts(uint64_t counted) {
    for (int k = 0; k < kStageCount; ++k) {
      StageRecord& r = r_.stages[size_t(k)];
      tx_end(k, r_.cycles_rtl);
      const uint64_t extra = counted > r_.cycles_rtl ? counted - r_.cycles_rtl : 0;
      if (r.starved < extra) {
        mismatch(std::string("stage statistics: ") + kStageNames[k] + " was not starved after the last busy cycle");
        continue;
      }
      r.starved -= extra;
    }
  }

  // ---- Port packing ----
  // The triangle port: assembly's offered item, coordinates masked to CoordW bits.
  void drive_triangle(bool valid) {
    top_->tri_valid_i = valid;
    if (!valid) return;
    const TbItem& it = s_.items[assembly_.item];
    const uint64_t coord_mask = (uint64_t{1} << p_.coord_w) - 1;
    top_->tri_marker_i = it.kind == TbItem::Marker;
    top_->tri_x0_i = static_cast<uint64_t>(it.x[0]) & coord_mask;
    top_->tri_y0_i = static_cast<uint64_t>(it.y[0]) & coord_mask;
    top_->tri_x1_i = static_cast<uint64_t>(it.x[1]) & coord_mask;
    top_->tri_y1_i = static_cast<uint64_t>(it.y[1]) & coord_mask;
    top_->tri_x2_i = static_cast<uint64_t>(it.x[2]) & coord_mask;
    top_->tri_y2_i = static_cast<uint64_t>(it.y[2]) & coord_mask;
    top_->tri_z0_i = it.z[0];
    top_->tri_z1_i = it.z[1];
    top_->tri_z2_i = it.z[2];
    top_->tri_rgb0_i = it.rgb[0];
    top_->tri_rgb1_i = it.rgb[1];
    top_->tri_rgb2_i = it.rgb[2];
    top_->tri_clip_x0_i = it.clip[0];
    top_->tri_clip_y0_i = it.clip[1];
    top_->tri_clip_x1_i = it.clip[2];
    top_->tri_clip_y1_i = it.clip[3];
    top_->tri_origin_x_i = it.origin[0];
    top_->tri_origin_y_i = it.origin[1];
  }
  // Lane j of the fragment port.
  Fragment lane_fragment(int j) const {
    Fragment f;
    f.x = static_cast<int>(port_bits(top_->frag_x_o, j * p_.pixel_w, p_.pixel_w));
    f.y = static_cast<int>(port_bits(top_->frag_y_o, j * p_.pixel_w, p_.pixel_w));
    f.z = static_cast<uint32_t>(port_bits(top_->frag_z_o, j * p_.depth_w, p_.depth_w));
    f.r = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24, 8));
    f.g = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24 + 8, 8));
    f.b = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24 + 16, 8));
    f.mask = static_cast<uint16_t>(port_bits(top_->frag_mask_o, j * p_.max_samples, p_.max_samples));
    f.samples = static_cast<uint8_t>(s_.samples);
    return f;
  }
  // A taken beat: a marker, or up to interp.fragments_per_cycle fragments, each compared
  // in order with the reference; a marker or a tile's last beat completes the batch.
  void take_beat(uint64_t t) {
    if (top_->frag_marker_o) {
      if (markers_in_flight_.empty()) {
        mismatch("cycle " + std::to_string(t) + ": a marker the testbench never sent");
      } else {
        staging_.marker = true;
        staging_.marker_item = markers_in_flight_.front();
        markers_in_flight_.pop_front();
      }
    } else {
      for (int j = 0; j < p_.interp_fragments_per_cycle; ++j) {
        if (!(port_bits(top_->frag_lanes_o, j, 1) & 1)) continue;
        ++staging_.fragments;
        staging_.frags.push_back(lane_fragment(j));
        const uint64_t acc = TimingParams::rop_accesses(staging_.frags.back().mask, s_.samples);
        staging_.accesses += acc;
        r_.rop_accesses += acc;
        compare(staging_.frags.back());
      }
    }
    if (top_->frag_marker_o || top_->frag_last_o) push_staging(t);
  }

  // ---- Checks ----
  void mismatch(const std::string& what) {
    if (r_.first_mismatch.empty()) r_.first_mismatch = what;
    ++r_.mismatches;
  }
  void compare(const Fragment& f) {
    ++r_.fragments_compared;
    if (next_expected_ >= s_.expected.size()) {
      mismatch("extra fragment from the RTL: " + fragment_trace_line(f));
      return;
    }
    const Expected& e = s_.expected[next_expected_++];
    if (!(e.f == f))
      mismatch("fragment #" + std::to_string(next_expected_ - 1) + " of " + s_.tri_names[e.tri] + ": pixel (" +
               std::to_string(e.f.x) + ", " + std::to_string(e.f.y) + ") expected '" + fragment_trace_line(e.f) +
               "' mask " + std::to_string(e.f.mask) + ", RTL gave '" + fragment_trace_line(f) + "' mask " +
               std::to_string(f.mask));
  }
  // Nothing left anywhere: scene fetched, FIFOs and stages empty, the RTL idle (its
  // idle_o covers the interpolator's pipeline) with no beat out, the ROP done.
  bool done() const { return rop_left_ == 0 && done_but_rop(); }
  bool done_but_rop() const {
    return next_item_ >= s_.items.size() && !fetch_.active && cmd_fifo_.empty() && !assembly_.active &&
           top_->idle_o && !top_->frag_valid_o &&
           !staging_blocked_ && staging_.fragments == 0 && !staging_.marker && frag_fifo_.empty() &&
           d2_fifo_.empty() && !fe_.active && op2d_fifo_.empty() && held_ < 0 && !engine_busy_ && !rop_wait_2d_;
  }
  void end_of_run_check() {
    if (next_expected_ < s_.expected.size())
      mismatch(std::to_string(s_.expected.size() - next_expected_) + " fragments missing from the RTL, first: #" +
               std::to_string(next_expected_) + " of " + s_.tri_names[s_.expected[next_expected_].tri] + ": '" +
               fragment_trace_line(s_.expected[next_expected_].f) + "'");
    if (!markers_in_flight_.empty()) mismatch(std::to_string(markers_in_flight_.size()) + " markers lost in the RTL");
    // The whole picture: the testbench framebuffer (fragments, clears and the 2D engine's
    // writes) against the reference model's.
    // Multisampled: the resolved image (the reference's is resolved by render_scene).
    const Framebuffer resolved = fb_.resolve();
    r_.samples = s_.samples;
    r_.crc_rtl = resolved.color_crc32();
    r_.crc_ref = s_.reference.color_crc32();
    for (int y = 0; y < resolved.height && r_.crc_rtl != r_.crc_ref; ++y)
      for (int x = 0; x < resolved.width; ++x)
        if (std::memcmp(resolved.pixel(x, y), s_.reference.pixel(x, y), 3) != 0) {
          mismatch("framebuffer pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") differs from the reference");
          return;
        }
  }

  const TbSetup& s_;
  const RtlParams& p_;
  CosimResult& r_;
  std::mt19937_64 rng_;
  std::bernoulli_distribution stall_;
  const size_t cmd_depth_, frag_depth_;  // command FIFO; fragment FIFO with the interpolator's latency slots
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> top_;
  std::unique_ptr<Vrast_engine2d> engine_;
  std::unique_ptr<VerilatedFstC> fst_;
  uint64_t time_ = 0;  // half cycles, the waveform's time

  std::deque<Entry> cmd_fifo_;
  std::deque<Batch> frag_fifo_;
  std::deque<size_t> markers_in_flight_;  // marker items sent to the RTL, in order
  Batch staging_;                         // the batch the interpolator is filling
  bool staging_blocked_ = false;          // completed, waiting for fragment-FIFO room
  TbStage fetch_, assembly_;
  size_t next_item_ = 0;
  uint64_t rop_left_ = 0;                 // ROP busy cycles left
  uint64_t last_busy_ = 0;                // last cycle any stage worked
  size_t next_expected_ = 0;
  // The 2D path.
  const size_t d2_depth_, op2d_depth_;
  RasterState st_;                        // the ROP's state (depth function, clears)
  Framebuffer fb_;                        // the memory: fragments, clears, 2D writes
  std::deque<Entry> d2_fifo_, op2d_fifo_;  // fetch -> front end -> engine (items: work2d indices)
  TbStage fe_;                            // the 2D front end
  bool fe_blocked_ = false;               // the front end waited for op2d FIFO room
  bool fetch_blocked_ = false;            // fetch waited for command or 2D FIFO room
  bool fetch_2d_pushed_ = false;          // fetch pushed its 2D command, the marker still to go
  int held_ = -1;                         // the batch the engine holds (work2d index)
  bool engine_busy_ = false;              // executing `held_` (the port is lent)
  bool engine_worked_ = false;            // the engine is busy in this cycle (stage statistics)
  size_t next_op_ = 0;                    // next operation of `held_` to offer
  bool rop_wait_2d_ = false;              // the ROP holds for the engine
  int grant_work_ = -1;                   // the 2D command the ROP granted
  // Stage statistics.
  struct Meter {
    bool open = false;  // a transaction is in progress
    uint64_t start = 0;  // its first cycle
  };
  std::array<Meter, kStageCount> meter_{};
  std::array<bool, 4> rtl_blocked_{};     // RTL stage s was stalled on its output last cycle
  bool assembly_offered_ = false;         // assembly offered its triangle in an earlier cycle
};

template <class V>
void run_rtl(const TbSetup& s, CosimResult& r) {
  RtlBench<V>(s, r).run();
}

}  // namespace rastsim::cosim
