// SPDX-License-Identifier: Apache-2.0
// The co-simulation testbench (testbench.h): everything of a run but the verilated
// models, which it reaches through RastPorts.
//
// Timing convention (the same as the RTL's and, shifted by nothing, the SystemC
// model's): a stage that takes an item in cycle u and needs n cycles offers its result
// in cycle u + n - 1; a FIFO entry pushed in cycle v is visible in cycle v + 1 (SystemC
// time v + 1); a push into a full FIFO succeeds when the reader pops in the same cycle.
// The testbench stages below follow model/sc/command_fetch.cpp, front_end.cpp and
// prim_assembly.cpp exactly, with the cost equations of TimingParams; the cycle count is
// the last cycle any stage (the RTL's ROP last) works + 1, as the model's.
//
// The ROP is rast_top's (rtl/rast_rop.sv behind the fragment FIFO). The testbench feeds
// its command port, one command a marker in stream order (a clear's value, else a pass),
// and serves its memory port from the framebuffer (memory.model = "fixed": every request
// taken at once, a read's data in the next cycle; "dram": taken at once, a read's data
// when its group's line fills have arrived, tb_rop_memory.h). What stays the testbench's: the 2D
// engine's grant of the ROP's port (a 2D marker's command is held back until the engine
// is done) and the multisample resolve pass (after the end-of-frame marker's command,
// TimingParams::resolve_cycles counted as ROP busy cycles).
//
// Stage statistics (docs/microarchitecture.md "Stage statistics"): every cycle each
// stage is busy, stalled or starved, as the SystemC Stage accounts it. The testbench
// stages (the geometry front end, the 2D front end and engine too) count their own
// cycles; setup, coarse raster, fine raster, interpolation and the ROP are classified
// from rast_top's dbg_has_o / dbg_done_o / dbg_blocked_o handshake ports.
//
// Stress (CosimOptions): random backpressure on the ROP's memory port (rd_ready_i and
// wr_ready_i low) and the 2D engine's (its ready inputs low, its read response delayed:
// a generator of its own, drawn only while the engine works) and random gaps in tri_valid_i and the 2D engine's in_valid_i, each from its own generator seeded by
// CosimOptions::stress_seed, drawn only when its probability is above 0 (so a run
// without stress, or with backpressure only, is the same run as before either existed).
#include "rtlsim/testbench.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <utility>

#include "ref/fixed_point.h"
#include "rtlsim/tb_hiz.h"
#include "rtlsim/tb_rop_memory.h"
#include "rtlsim/tb_texture.h"
#include "ref/pipeline.h"
#include "timing/stage_table.h"

namespace rastsim::rtlsim {

namespace {

// A testbench stage: takes an item, is busy `cost` cycles, offers its output in the
// last of them and holds it until taken.
struct TbStage {
  bool active = false;
  uint64_t left = 0;  // busy cycles left, including the current one
  size_t item = 0;
  bool offering() const { return active && left == 1; }
};

enum class Cyc : uint8_t { Starved, Busy, Stalled };  // a stage's state in one cycle

// The RTL stages rast_top's dbg_*_o ports observe, bit s of each port.
constexpr std::array kObservedStages = {StageId::TriSetup, StageId::CoarseRaster, StageId::FineRaster,
                                        StageId::Interpolate, StageId::Rop};
constexpr size_t kRopBit = 4;  // the ROP's bit of rast_top's dbg_*_o

// A FIFO entry, visible to its reader from the cycle after its push: a command-FIFO
// entry (a scene item) or a 2D FIFO entry (a work2d index).
struct Entry {
  size_t item;
  uint64_t pushed;
};
// A screen-FIFO entry: a triangle item (-1: its command's end), visible to assembly
// from cycle `visible` (after the push and the front end's pipeline latency).
struct ScreenEntry {
  int64_t item;
  uint64_t visible;
};
// A marker's command on rast_rop's cmd_op_i / cmd_value_i: 1 clears colour to
// {a = 255, b, g, r}, 2 clears depth to the unorm value; 0 passes.
struct RopCommand {
  int op = 0;
  uint32_t value = 0;
};
RopCommand rop_command(const Command& cmd, int depth_bits) {
  RopCommand r;
  visit_command(cmd, Overloaded{
      [&](const CmdViewport&) {},
      [&](const CmdScissor&) {},
      [&](const CmdPrimitives&) {},
      [&](const CmdDraw2d&) {},
      [&](const CmdClear& c) { r = {1, uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | 0xffu << 24}; },
      [&](const CmdClearDepth& c) { r = {2, quantize_unorm(c.z, depth_bits).value_or(0)}; },
  });
  return r;
}

// A random low on one valid or ready input, with probability p a cycle (0: never, and
// no number drawn).
class PortStress {
 public:
  PortStress(std::mt19937_64 rng, double p) : rng_(rng), p_(p), low_(p) {}
  bool low() { return p_ > 0 && low_(rng_); }

 private:
  std::mt19937_64 rng_;
  double p_;
  std::bernoulli_distribution low_;
};
// The memory port's generator is seeded with the seed itself, each valid input's with the
// seed and its own index (port 1, 2, ...).
std::mt19937_64 port_rng(uint64_t seed, uint32_t port) {
  if (port == 0) return std::mt19937_64(seed);
  std::seed_seq seq{uint32_t(seed), uint32_t(seed >> 32), port};
  return std::mt19937_64(seq);
}

// One co-simulation run: the verilated rast_top between the testbench's front end
// (command fetch, command FIFO, the geometry front end with its clip-command and screen
// FIFOs, primitive assembly) and the memory behind its ROP. Each cycle: the ROP's
// command and the memory's answers are driven, assembly acts on what is visible, the
// triangle port is driven, the clock falls, the fragment port and the ROP's requests are
// read and served, assembly and fetch advance, the clock rises.
class Testbench {
 public:
  Testbench(const TbSetup& setup, RastPorts& ports, CosimResult& result)
      : setup_(setup), ports_(ports), result_(result),
        mem_ready_stress_(port_rng(setup.opts.stress_seed, 0), setup.opts.backpressure),
        tri_valid_stress_(port_rng(setup.opts.stress_seed, 1), setup.opts.valid_gaps),
        op_valid_stress_(port_rng(setup.opts.stress_seed, 2), setup.opts.valid_gaps),
        engine_mem_stress_(port_rng(setup.opts.stress_seed, 3), setup.opts.backpressure),
        cmd_depth_(size_t(setup.timing.fifo_entries(FifoId::Command))),
        draw2d_depth_(size_t(setup.timing.fifo_entries(FifoId::Draw2d))),
        op2d_depth_(size_t(setup.timing.fifo_entries(FifoId::Op2d))),
        clip_depth_(size_t(setup.timing.fifo_entries(FifoId::ClipCommand))),
        screen_depth_(size_t(setup.timing.fifo_entries(FifoId::Screen))),
        fb_(setup.arch.fb_width, setup.arch.fb_height, setup.samples),
        depth_base_(rop_depth_base(fb_.width, fb_.height, fb_.samples)), texture_(setup), hiz_(setup) {
    fb_.clear_depth(static_cast<uint32_t>((uint64_t{1} << setup.arch.depth_bits) - 1));  // as render_scene
    if (setup.opts.initial_fb) fb_ = *setup.opts.initial_fb;  // cosim --frames: the frames before the range
    if (setup.memory.enabled) {
      dram_ = std::make_unique<TbRopMemory>(setup);
      texture_.attach(dram_->system());  // after the scan-out and the ROP, as simulate attaches it
      hiz_.attach(dram_->system());
    }
    for (size_t i = 0; i < setup.items.size(); ++i)
      if (!setup.items[i].from_front_end && !setup.items[i].fed) fetched_.push_back(i);
    if (setup.hiz && !setup.binned) {  // each pixel's expected depth writes, in order
      depth_writes_.resize(size_t(fb_.width) * size_t(fb_.height));
      for (const TbDepthWrite& w : setup.depth_writes)
        depth_writes_[size_t(w.y) * size_t(fb_.width) + size_t(w.x)].push_back(w.z);
    }
    if (setup.binned)
      binner_ = std::make_unique<TbBinner>(
          setup, dram_ ? &dram_->system() : nullptr, [this](const std::string& m) { mismatch(m); },
          [this](uint32_t a, uint64_t t) { return rop_read_word(a, t); },
          [this](uint32_t a, uint32_t d, uint64_t t) { rop_write_word(a, d, 0xfu, t); });
  }

  void run();

 private:
  void reset();
  bool cycle(uint64_t t);
  // Back end: the ROP's command feed and the memory behind its port.
  void rop_drive(uint64_t t);
  void rop_serve(uint64_t t);
  void rop_command_taken(uint64_t t);
  bool rop_decode(uint32_t addr, uint64_t t, bool& depth, int& x, int& y, int& s);
  uint32_t rop_read_word(uint32_t addr, uint64_t t);
  void rop_write_word(uint32_t addr, uint32_t data, uint32_t be, uint64_t t);
  void rop_fill(const RopLane& l, uint32_t data, uint32_t be, uint64_t t);
  void take_beat(uint64_t t, const FragmentBeat& beat);
  // The 2D path (model/sc/draw2d_setup.cpp, engine2d.cpp).
  void engine_take(uint64_t t);
  void engine_done(uint64_t t);
  bool engine_drive();
  uint32_t fb_rgb(int x, int y) const;
  void engine_memory_and_handshake(uint64_t t, bool op_valid);
  void engine_read(const Engine2dAccess& a);
  void engine_write(uint64_t t, int x, int y);
  void front_end_take(uint64_t t);
  void front_end_step(uint64_t t);
  bool front_end_push(uint64_t t, Cyc& state);
  static bool try_push(std::deque<Entry>& fifo, size_t depth, const Entry& e, bool& blocked, Cyc& state);
  template <class Take, class Push>
  void step_stage(StageId k, uint64_t t, TbStage& st, const bool& blocked, Take take, Push push);
  // The geometry front end (model/sc/front_end.cpp).
  void geometry_take(uint64_t t);
  void geometry_step(uint64_t t);
  bool geometry_push(uint64_t t, Cyc& state);
  // Front end: command fetch and primitive assembly (model/sc/command_fetch.cpp, prim_assembly.cpp).
  void assembly_take(uint64_t t);
  void assembly_step(uint64_t t, bool tri_taken);
  void fetch_step(uint64_t t);
  bool fetch_push(uint64_t t, Cyc& state);
  // Stage statistics.
  StageRecord& record(StageId k) { return result_.stages[stage_index(k)]; }
  void count(StageId k, Cyc c);
  void tx_begin(StageId k, uint64_t t);
  void tx_end(StageId k, uint64_t t);
  void observe_rtl_stages(uint64_t t);
  void observe_rop(uint64_t t, const RtlStageBits& bits);
  void close_stage_counts(uint64_t counted);
  // Checks.
  void mismatch(const std::string& what);
  void compare(const Fragment& f, bool culled);
  void skip_hiz_culled(const Fragment& f);
  void depth_write_check(int x, int y, uint32_t v, uint64_t t);
  void hiz_count_check();
  void early_serve();  // depth.early: the early test's depth read, answered in its cycle
  bool done() const { return resolve_left_ == 0 && done_but_rop(); }
  bool done_but_rop() const;
  void end_of_run_check();
  void framebuffer_check();

  const TbSetup& setup_;
  RastPorts& ports_;
  CosimResult& result_;
  PortStress mem_ready_stress_, tri_valid_stress_, op_valid_stress_;
  PortStress engine_mem_stress_;  // the 2D engine's rd_ready_i, wr_ready_i and response delay
  const size_t cmd_depth_;  // command FIFO
  const size_t draw2d_depth_, op2d_depth_;  // the 2D command and operation FIFOs
  const size_t clip_depth_, screen_depth_;  // the clip-command FIFO; the screen FIFO with the front end's latency slots

  std::deque<Entry> cmd_fifo_;
  std::deque<size_t> markers_in_flight_;  // marker items sent to the RTL, in order
  std::deque<size_t> rop_commands_;       // markers out of the interpolator, their commands not yet taken
  TbStage fetch_, assembly_;
  std::vector<size_t> fetched_;           // the items fetch takes, in order (not the front end's triangles)
  size_t next_item_ = 0;                  // next of fetched_
  uint64_t resolve_left_ = 0;             // the resolve pass's ROP cycles left
  uint64_t last_busy_ = 0;                // last cycle any stage worked
  size_t next_expected_ = 0;
  // Hi-Z (immediate mode): each pixel's depth writes the reference's ROP makes, in order,
  // popped as the RTL's ROP makes them (index y W + x; empty: not checked).
  std::vector<std::deque<uint32_t>> depth_writes_;
  int64_t hiz_tile_drawn_ = -1;           // lagged: the reference-culled tile the RTL is drawing
  // The memory behind the ROP's port: the framebuffer (docs/rtl.md "ROP" for the layout).
  Framebuffer fb_;                        // the memory: the ROP's writes and clears, 2D writes
  const uint32_t depth_base_;             // the depth surface's byte address (colour at 0)
  bool read_pending_ = false;             // a read taken, its data not yet returned
  uint64_t read_due_ = 0;                 // the cycle its data returns
  std::vector<uint32_t> read_data_;       // lane k word i at k MaxSamples + i
  std::array<uint32_t, 2> fill_next_{};   // a clear's next word address per surface (colour, depth)
  bool read_ready_ = false, write_ready_ = false;  // rd_ready_i, wr_ready_i this cycle
  bool command_valid_ = false;            // cmd_valid_i this cycle
  int command_op_ = 0;                    // cmd_op_i this cycle
  uint64_t perturb_now_ = 0;              // CosimOptions::perturb_rop_*: the next read's extra latency
  std::unique_ptr<TbRopMemory> dram_;     // memory.model = "dram": the timed memory system (null: fixed)
  std::unique_ptr<TbBinner> binner_;      // pipeline.mode = binned: the binner and the tile buffer's memory
  TbTexture texture_;                     // the texel memory behind the texel fetch port
  TbHiz hiz_;                             // Hi-Z's spilled entries behind hiz_mem_*
  bool hiz_overflow_ = false;             // dbg_hiz_error_o seen
  // The 2D path.
  std::deque<Entry> draw2d_fifo_, op2d_fifo_;  // fetch -> front end -> engine (items: work2d indices)
  TbStage front_end_;                     // the 2D front end
  bool front_end_blocked_ = false;        // the front end waited for op2d FIFO room
  bool fetch_blocked_ = false;            // fetch waited for command or 2D FIFO room
  bool fetch_job_pushed_ = false;         // fetch pushed its 2D or clip-space job, the marker still to go
  int engine_work_ = -1;                  // the batch the engine holds (work2d index)
  bool engine_busy_ = false;              // executing `engine_work_` (the port is lent)
  bool engine_worked_ = false;            // the engine is busy in this cycle (stage statistics)
  size_t next_op_ = 0;                    // next operation of `engine_work_` to offer
  bool rop_wait_2d_ = false;              // the ROP's port is lent to the engine
  bool rop_2d_done_ = false;              // the engine is done: the 2D marker's command goes to the ROP
  int granted_work_ = -1;                 // the 2D command the ROP granted
  bool engine_rsp_pending_ = false;       // the engine's read was taken, its response not yet driven
  std::vector<uint32_t> engine_rsp_d_;    // that response: D of each lane, S
  uint32_t engine_rsp_s_ = 0;
  uint64_t engine_op_end_ = 0;            // dram: the current operation's fills used (its last write from end - 1)
  // Stage statistics.
  struct Meter {
    bool open = false;   // a transaction is in progress
    uint64_t start = 0;  // its first cycle
  };
  std::array<Meter, kStageCount> meter_{};
  std::array<bool, kObservedStages.size()> rtl_blocked_{};  // observed stage s was stalled on its output last cycle
  bool assembly_offered_ = false;         // assembly offered its triangle in an earlier cycle
  bool assembly_clip_ = false;            // assembly takes a clip-space command's triangles from the screen FIFO
  // The geometry front end: clip-space jobs (items) from fetch, triangles to assembly.
  std::deque<Entry> clip_fifo_;
  std::deque<ScreenEntry> screen_fifo_;
  TbStage geometry_;                      // item: the ClipCommand; left: the current step's cycles
  size_t geometry_next_step_ = 0, geometry_end_step_ = 0;  // the current step, the job's end (front_end_steps)
  bool geometry_blocked_ = false;         // the step's push waits for screen-FIFO room
  uint64_t geometry_attempt_ = 0;         // the cycle of that push's first attempt (its latency counts from it)
};

void Testbench::run() {
  const auto t0 = std::chrono::steady_clock::now();
  result_.stages.assign(kStageCount, StageRecord{});
  for (const StageInfo& s : kStages) record(s.id).name = std::string(s.name);
  result_.command_starts.assign(setup_.commands, UINT64_MAX);
  result_.command_mismatches.assign(setup_.commands, 0);
  reset();
  uint64_t counted = 0;  // cycles classified (0 .. the last one run)
  for (uint64_t t = 0;; ++t) {
    counted = t + 1;
    if (t >= setup_.opts.max_cycles) {
      mismatch("simulation did not finish within " + std::to_string(setup_.opts.max_cycles) + " cycles");
      break;
    }
    if (cycle(t)) {
      result_.cycles_rtl = last_busy_ + 1;
      break;
    }
    // Only the resolve pass left (a multisampled frame's: up to millions of cycles): skip
    // to its last cycle instead of clocking an idle RTL (the waveform stops here).
    if (resolve_left_ > 1 && done_but_rop()) {
      last_busy_ = std::max(last_busy_, t + resolve_left_);
      result_.cycles_rtl = last_busy_ + 1;
      // The skipped cycles t + 1 .. t + resolve_left_: the ROP busy, every other stage starved.
      for (const StageInfo& s : kStages)
        (s.id == StageId::Rop ? record(s.id).busy : record(s.id).starved) += resolve_left_;
      counted = t + 1 + resolve_left_;
      resolve_left_ = 0;
      break;
    }
  }
  close_stage_counts(counted);
  if (dram_) dram_->finish(result_.cycles_rtl, result_);
  {
    std::string error;
    texture_.finish(result_, error);
    if (!error.empty()) mismatch(error);
    error.clear();
    if (setup_.hiz) hiz_.finish(result_, error);
    if (!error.empty()) mismatch(error);
  }
  if (result_.helper_pixels != setup_.helper_pixels)
    mismatch("helper pixels: the RTL dropped " + std::to_string(result_.helper_pixels) + ", the reference counts " +
             std::to_string(setup_.helper_pixels));
  hiz_count_check();
  result_.hiz = setup_.hiz;
  result_.hiz_lagged = setup_.hiz_lagged;
  result_.depth_early = setup_.depth_early;
  if (result_.fragments_culled_early != setup_.fragments_culled_early)
    mismatch("early Z: the RTL culled " + std::to_string(result_.fragments_culled_early) + " fragments, the reference " +
             std::to_string(setup_.fragments_culled_early));
  end_of_run_check();
  ports_.finish();
  result_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Static raster state on its ports, then one reset cycle.
void Testbench::reset() {
  ports_.drive_static(setup_);
  ports_.clock_edge(false);
  ports_.clock_edge(true);
  ports_.release_reset();
}

// One clock cycle t; true when the run is complete.
bool Testbench::cycle(uint64_t t) {
  rop_drive(t);
  engine_take(t);
  front_end_take(t);
  front_end_step(t);
  bool op_valid = engine_drive();
  assembly_take(t);
  // Binned: assembly hands its items to the binner, which feeds rast_top (tb_binning.h).
  const TbItem* fed = binner_ ? binner_->feed(t) : nullptr;
  const bool tri_valid = (binner_ ? fed != nullptr : assembly_.offering()) && !tri_valid_stress_.low();
  ports_.drive_triangle(!tri_valid ? nullptr : binner_ ? fed : &setup_.items[assembly_.item]);
  texture_.drive(t, ports_);
  hiz_.drive(t, ports_);
  ports_.clock_edge(false);
  if (setup_.depth_early) early_serve();  // first: its answer changes rast_top's outputs
  bool tri_taken = tri_valid && ports_.triangle_ready();
  if (binner_) {
    binner_->advance(t, tri_taken, markers_in_flight_);
    tri_taken = binner_->take(t, assembly_.offering() ? &setup_.items[assembly_.item] : nullptr, assembly_.item);
    if (!binner_->done()) last_busy_ = std::max(last_busy_, t);
  }
  {
    std::string error;
    texture_.serve(t, ports_, error);
    if (!error.empty()) mismatch(error);
    error.clear();
    hiz_.serve(t, ports_, error);
    if (ports_.hiz_request().error && !hiz_overflow_) {  // sticky in the RTL: reported once
      hiz_overflow_ = true;
      error = "cycle " + std::to_string(t) + ": Hi-Z's spilled-entry write FIFO overflowed";
    }
    if (!error.empty()) mismatch(error);
    result_.helper_pixels += uint64_t(ports_.helper_pixels());
  }
  observe_rtl_stages(t);
  const FragmentBeat beat = ports_.fragment_beat();
  if (!ports_.idle() || beat.valid || fetch_.active || assembly_.active) last_busy_ = std::max(last_busy_, t);
  if (beat.valid && ports_.fragment_taken()) take_beat(t, beat);
  const bool granted = rop_wait_2d_;
  rop_serve(t);
  if (binner_) binner_->serve_port(t, ports_);  // after rop_serve: a load or store starts with its command
  // A grant made now (the 2D marker waits at the quiet ROP): the engine takes the port and
  // is offered its first operation in this cycle, as the model's engine reads the grant
  // the ROP writes (drive_engine_read evaluates it again).
  if (!granted && rop_wait_2d_) {
    engine_take(t);
    op_valid = engine_drive();
  }
  engine_memory_and_handshake(t, op_valid);
  assembly_step(t, tri_taken);
  geometry_step(t);
  fetch_step(t);
  ports_.clock_edge(true);
  return done();
}

// ---- Back end: the ROP's commands and memory (rtl/rast_rop.sv's ports) ----

// Before the clock falls: the memory's answer to the read taken earlier (its data in the
// cycle after, or later under CosimOptions::perturb_rop_*), both ready inputs (low at
// random under backpressure stress), and the head marker's command: a clear's value, a
// pass; a 2D marker's only once the engine is done with the port.
void Testbench::rop_drive(uint64_t t) {
  const bool respond = read_pending_ && read_due_ <= t;
  ports_.drive_rop_response(respond, read_data_);
  if (respond) read_pending_ = false;
  read_ready_ = !mem_ready_stress_.low();
  write_ready_ = !mem_ready_stress_.low();
  ports_.drive_rop_memory_ready(read_ready_, write_ready_);
  if (binner_) binner_->drive_port(t, ports_);
  command_valid_ = false;
  if (rop_commands_.empty()) {
    ports_.drive_rop_command(false, 0, 0);
    return;
  }
  const TbItem& m = setup_.items[rop_commands_.front()];
  command_valid_ = m.work2d < 0 || rop_2d_done_;
  if (m.bin_marker >= 0) {  // binned: a bin command (tb_binning.h)
    const TbBinMarker& b = setup_.binning.markers[size_t(m.bin_marker)];
    command_op_ = b.op >= 4 ? 0 : b.op;  // a bin command is a pass at the ROP
    ports_.drive_rop_command(command_valid_, b.op, b.value, b.rect);
    return;
  }
  const RopCommand c = m.cmd ? rop_command(*m.cmd, setup_.arch.depth_bits) : RopCommand{};  // none: the frame end
  command_op_ = c.op;
  ports_.drive_rop_command(command_valid_, c.op, c.value);
}
// After the clock falls: the ROP's write (before its read: the memory orders a read after
// every write it took in the same cycle), its read (the data read now, returned later),
// and its command port (a command taken; a 2D marker waiting at the quiet ROP: the grant).
void Testbench::rop_serve(uint64_t t) {
  if (write_ready_ && ports_.rop_write_valid()) {
    const int lanes = 2 * setup_.params.rop_pixels_per_cycle;
    if (ports_.rop_write_fill()) {
      rop_fill(ports_.rop_write_lane(0), ports_.rop_write_data(0), ports_.rop_write_enables(0, 0), t);
    } else {
      for (int k = 0; k < lanes; ++k) {
        if (!ports_.rop_write_lane_valid(k)) continue;
        const RopLane l = ports_.rop_write_lane(k);
        for (uint32_t i = 0; i < l.len; ++i)
          rop_write_word(l.addr + 4 * i, ports_.rop_write_data(k), ports_.rop_write_enables(k, int(i)), t);
      }
    }
  }
  if (read_ready_ && ports_.rop_read_valid()) {
    const int ms = setup_.params.max_samples;
    if (read_pending_) mismatch("cycle " + std::to_string(t) + ": the ROP read again before its read's data");
    read_data_.assign(size_t(setup_.params.rop_pixels_per_cycle * ms), 0);
    uint32_t accesses = 0;  // one a lane
    const bool no_depth = ports_.rop_read_no_depth();  // a Hi-Z accepted tile's group: no depth read
    for (int k = 0; k < setup_.params.rop_pixels_per_cycle; ++k) {
      if (!ports_.rop_read_lane_valid(k)) continue;
      ++accesses;
      const RopLane l = ports_.rop_read_lane(k);
      if (l.len > uint32_t(ms)) mismatch("cycle " + std::to_string(t) + ": a read burst longer than MaxSamples");
      for (uint32_t i = 0; i < l.len && i < uint32_t(ms) && !no_depth; ++i)
        read_data_[size_t(k * ms) + i] = rop_read_word(l.addr + 4 * i, t);
    }
    read_pending_ = true;
    read_due_ = (dram_ ? dram_->read(t, accesses, no_depth) : t + 1) + std::exchange(perturb_now_, 0);
  }
  if (rop_commands_.empty() || !ports_.rop_command_wanted()) return;
  const TbItem& m = setup_.items[rop_commands_.front()];
  if (command_valid_ && m.bin_marker >= 0) {  // binned: the tile buffer starts its load or store
    rop_commands_.pop_front();
    binner_->command(t, setup_.binning.markers[size_t(m.bin_marker)]);
  } else if (command_valid_) {
    rop_commands_.pop_front();
    rop_2d_done_ = false;
    if (!m.cmd) resolve_left_ = dram_ ? dram_->frame_end(t, m.rop_cost) : m.rop_cost;  // the frame end: its marker's cycle, then the resolve pass
    else if (dram_ && m.work2d < 0) dram_->command(*m.cmd, t);
  } else if (m.work2d >= 0 && !rop_wait_2d_ && !rop_2d_done_) {
    rop_wait_2d_ = true;  // the engine takes the port in this cycle (cycle: engine_take again)
    granted_work_ = m.work2d;
  }
}
// The surface, pixel and sample of a byte address (false: none, a mismatch reported).
bool Testbench::rop_decode(uint32_t addr, uint64_t t, bool& depth, int& x, int& y, int& s) {
  depth = addr >= depth_base_;
  const uint64_t off = addr - (depth ? depth_base_ : 0);
  if (off % 4 != 0 || off >= depth_base_) {
    mismatch("cycle " + std::to_string(t) + ": the ROP addressed byte " + std::to_string(addr) +
             ", outside its surfaces or not a word");
    return false;
  }
  const uint64_t word = off / 4, pixel = word / uint64_t(fb_.samples);
  s = int(word % uint64_t(fb_.samples));
  x = int(pixel % uint64_t(fb_.width));
  y = int(pixel / uint64_t(fb_.width));
  return true;
}
uint32_t Testbench::rop_read_word(uint32_t addr, uint64_t t) {
  bool depth = false;
  int x = 0, y = 0, s = 0;
  if (!rop_decode(addr, t, depth, x, y, s)) return 0;
  if (depth) return fb_.depth_at(x, y, s);
  uint32_t v = 0;
  std::memcpy(&v, std::as_const(fb_).sample(x, y, s), 4);  // bytes {r, g, b, a}, little-endian word
  return v;
}
void Testbench::rop_write_word(uint32_t addr, uint32_t data, uint32_t be, uint64_t t) {
  if (be == 0) return;
  bool depth = false;
  int x = 0, y = 0, s = 0;
  if (!rop_decode(addr, t, depth, x, y, s)) return;
  uint32_t v = rop_read_word(addr, t);
  for (int b = 0; b < 4; ++b)
    if ((be >> b) & 1) v = (v & ~(0xffu << (8 * b))) | (data & (0xffu << (8 * b)));
  if (depth) {
    if (!depth_writes_.empty()) depth_write_check(x, y, v, t);
    fb_.set_depth(x, y, s, v);
  } else {
    std::memcpy(fb_.sample(x, y, s), &v, 4);
  }
}
// Hi-Z: the ROP's depth write v at (x, y) must be the reference's next write there (a
// fragment of a tile the reference culled, drawn by the lagged table, must fail its test).
void Testbench::depth_write_check(int x, int y, uint32_t v, uint64_t t) {
  std::deque<uint32_t>& q = depth_writes_[size_t(y) * size_t(fb_.width) + size_t(x)];
  const uint32_t mask = setup_.arch.depth_bits >= 32 ? ~0u : (1u << setup_.arch.depth_bits) - 1;
  if (!q.empty() && q.front() == (v & mask)) {
    q.pop_front();
    return;
  }
  mismatch("cycle " + std::to_string(t) + ": the ROP wrote depth " + std::to_string(v & mask) + " at (" +
           std::to_string(x) + ", " + std::to_string(y) + "), the reference's next write there is " +
           (q.empty() ? std::string("none") : std::to_string(q.front())) +
           (setup_.hiz_lagged ? " (lagged: a tile drawn or accepted against a stale bound?)" : ""));
}
// A clear's fill write: word 0's value and enables over the burst. The clear's writes
// cover its surface in address order; its last one applies the clear to the whole
// surface (as Framebuffer's clears: every tile at once, none materialised).
void Testbench::rop_fill(const RopLane& l, uint32_t data, uint32_t be, uint64_t t) {
  const bool depth = l.addr >= depth_base_;
  const uint32_t base = depth ? depth_base_ : 0;
  uint32_t& next = fill_next_[depth ? 1 : 0];
  if (l.addr != base && l.addr != next) {
    mismatch("cycle " + std::to_string(t) + ": a clear's write at byte " + std::to_string(l.addr) + ", expected " +
             std::to_string(next));
    return;
  }
  next = l.addr + 4 * l.len;
  if (next < base + depth_base_) return;
  if (next != base + depth_base_) mismatch("cycle " + std::to_string(t) + ": a clear's write past its surface");
  const uint32_t depth_mask = setup_.arch.depth_bits >= 32 ? ~0u : (1u << setup_.arch.depth_bits) - 1;
  const uint32_t want_be = depth ? (1u << ((setup_.arch.depth_bits + 7) / 8)) - 1 : 0xfu;
  if (be != want_be) mismatch("cycle " + std::to_string(t) + ": a clear's byte enables " + std::to_string(be));
  if (depth) fb_.clear_depth(data & depth_mask);
  else fb_.clear_color(uint8_t(data), uint8_t(data >> 8), uint8_t(data >> 16));
}
// A beat the fragment FIFO takes: a marker (its command next for the ROP), or up to
// interp.fragments_per_cycle fragments, each compared in order with the reference.
void Testbench::take_beat(uint64_t t, const FragmentBeat& beat) {
  if (beat.marker) {
    if (markers_in_flight_.empty()) {
      mismatch("cycle " + std::to_string(t) + ": a marker the testbench never sent");
    } else {
      rop_commands_.push_back(markers_in_flight_.front());
      markers_in_flight_.pop_front();
    }
    return;
  }
  for (int j = 0; j < setup_.params.interp_fragments_per_cycle; ++j) {
    if (!ports_.fragment_lane_valid(j)) continue;
    Fragment f = ports_.fragment_lane(j);
    f.samples = static_cast<uint8_t>(setup_.samples);
    result_.rop_accesses += TimingParams::rop_accesses(f.mask, setup_.samples);
    const bool culled = ports_.fragment_lane_culled(j);  // early Z: still the ROP's, for its depth reads
    result_.fragments_culled_early += culled ? 1 : 0;
    compare(f, culled);
    if (dram_) dram_->fragment(f);
  }
}

// ---- The 2D path (model/sc/draw2d_setup.cpp, engine2d.cpp) ----

// The engine takes the next visible operation batch when it has none.
void Testbench::engine_take(uint64_t t) {
  engine_worked_ = false;
  if (engine_work_ < 0 && !engine_busy_ && !op2d_fifo_.empty() && op2d_fifo_.front().pushed < t) {
    engine_work_ = int(op2d_fifo_.front().item);
    op2d_fifo_.pop_front();
    tx_begin(StageId::Engine2d, t);  // the model's read of the operation batch
  }
  // The ROP's grant and the held batch: the engine starts (its first cycle takes the port).
  if (rop_wait_2d_ && engine_work_ >= 0 && !engine_busy_) {
    if (engine_work_ != granted_work_)
      mismatch("2D engine holds " + setup_.work2d[size_t(engine_work_)].name + " but the ROP granted " +
               setup_.work2d[size_t(granted_work_)].name);
    engine_busy_ = true;
    engine_worked_ = true;  // the cycle that takes the port (TimingParams::engine2d_grant_cycles)
    next_op_ = 0;
    if (setup_.work2d[size_t(engine_work_)].work.ops.empty()) engine_done(t);
  }
}
// The engine's last busy cycle t: its transaction ends (the model's write of done
// returns at once: the ROP waits for it), the ROP takes the marker's command in t + 1.
void Testbench::engine_done(uint64_t t) {
  tx_end(StageId::Engine2d, t + 1);
  engine_busy_ = false;
  engine_work_ = -1;
  rop_wait_2d_ = false;
  rop_2d_done_ = true;  // the marker's command, next cycle: the ROP's own cycle for it
}
// Drives the next operation and the command's paint state; true when one is offered
// (none while the valid-gap stress holds in_valid_i low).
bool Testbench::engine_drive() {
  const bool has_op = engine_busy_ && next_op_ < setup_.work2d[size_t(engine_work_)].work.ops.size();
  if (!has_op || op_valid_stress_.low()) {
    ports_.drive_operation(nullptr, nullptr);
    return false;
  }
  const Draw2dWork& w = setup_.work2d[size_t(engine_work_)].work;
  ports_.drive_operation(&w, &w.ops[next_op_]);
  return true;
}
uint32_t Testbench::fb_rgb(int x, int y) const {
  if (x < 0 || y < 0 || x >= fb_.width || y >= fb_.height) return 0;
  const uint8_t* p = fb_.pixel(x, y);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16;
}
// The framebuffer port (asynchronous read, write at the edge), then the handshake.
// The engine's cycle is busy from the one that takes the port to the one whose
// operation completes the command (without valid gaps the testbench offers every
// operation at once, so the engine never waits: the model's busy(1) +
// busy(engine2d_op_cycles) per operation); starved otherwise (the model's reads of the
// operations and of the ROP's grant).
void Testbench::engine_memory_and_handshake(uint64_t t, bool op_valid) {
  engine_worked_ = engine_worked_ || engine_busy_;
  count(StageId::Engine2d, engine_worked_ ? Cyc::Busy : Cyc::Starved);
  if (!engine_busy_) return;
  last_busy_ = t;
  const Engine2dAccess a = ports_.engine_access();
  engine_read(a);
  engine_write(t, a.x, a.y);
  const Draw2dWork& w = setup_.work2d[size_t(engine_work_)].work;
  const bool all_taken = next_op_ >= w.ops.size();
  const bool ready = ports_.operation_ready();
  if (op_valid && ready) {
    // dram: the operation's accesses from its first cycle, t + 1 (the SystemC engine's
    // transaction start), on the timed memory system (TbRopMemory::operation_2d).
    if (dram_) engine_op_end_ = dram_->operation_2d(w, w.ops[next_op_], t + 1);
    ++next_op_;
  }
  if (all_taken && ready) engine_done(t);
}
// The engine's read: taken unless the backpressure stress holds rd_ready_i low, its data
// (the lanes and source asked for; 0 elsewhere) read from the framebuffer when taken,
// the response driven at once or, under the stress, some cycles later (the engine waits
// for it). Every read is answered at once without stress, with memory.model = "dram" too:
// the operation's fills hold its last write instead (engine_write).
void Testbench::engine_read(const Engine2dAccess& a) {
  const Engine2dRead r = ports_.engine_read();
  const bool ready = !engine_mem_stress_.low();
  if (r.valid && ready) {
    engine_rsp_pending_ = true;
    engine_rsp_d_.assign(size_t(engine2d_rtl_params().lanes_max), 0);
    for (size_t k = 0; k < engine_rsp_d_.size(); ++k)
      if ((r.lanes >> k) & 1) engine_rsp_d_[k] = fb_rgb(a.x + int(k), a.y);
    engine_rsp_s_ = r.source ? fb_rgb(a.sx, a.sy) : 0;
  }
  const bool rvalid = engine_rsp_pending_ && !engine_mem_stress_.low();
  if (rvalid) engine_rsp_pending_ = false;
  ports_.drive_engine_read(ready, rvalid, engine_rsp_d_, engine_rsp_s_);
}
// The engine's write, taken at this cycle's edge into the framebuffer, lane k at (x + k, y),
// the bytes its enables name. wr_ready_i is low under the backpressure stress, and with
// memory.model = "dram" for the operation's last write until its fills have been used:
// the operation lasts max(its work, last fill + 1 - start) cycles, as the SystemC
// engine's transaction (timing/memory_timing.h memory_transaction_cycles).
void Testbench::engine_write(uint64_t t, int x, int y) {
  const Engine2dWrite w = ports_.engine_write();
  bool ready = !engine_mem_stress_.low();
  if (dram_ && w.valid && w.last && t + 1 < engine_op_end_) ready = false;
  ports_.drive_engine_write_ready(ready);
  if (!w.valid || !ready) return;
  for (int k = 0; k < engine2d_rtl_params().lanes_max; ++k) {
    const uint32_t be = (w.byte_enables >> (3 * k)) & 7;
    if (be == 0) continue;
    if (x + k < 0 || y < 0 || x + k >= fb_.width || y >= fb_.height) {
      mismatch("cycle " + std::to_string(t) + ": the 2D engine wrote outside the framebuffer at (" +
               std::to_string(x + k) + ", " + std::to_string(y) + ")");
      continue;
    }
    const uint32_t v = ports_.engine_write_rgb(k);
    uint8_t* p = fb_.pixel(x + k, y);
    for (int b = 0; b < 3; ++b)
      if ((be >> b) & 1) p[b] = uint8_t(v >> (8 * b));
    p[3] = 255;
    ++result_.pixels_2d;
  }
}
// The 2D front end: takes a visible command, is busy its cost, pushes its operations.
void Testbench::front_end_take(uint64_t t) {
  if (!front_end_.active && !draw2d_fifo_.empty() && draw2d_fifo_.front().pushed < t) {
    front_end_ = TbStage{true, setup_.work2d[draw2d_fifo_.front().item].setup_cost, draw2d_fifo_.front().item};
    draw2d_fifo_.pop_front();
    tx_begin(StageId::Draw2dSetup, t);
  }
}
// A stage that pushes in its last busy cycle starts its next item the cycle after; one
// that was blocked on a full FIFO pushes in the cycle the reader pops and starts its
// next item in that same cycle (the SystemC writer returns from its blocked write then).
// The cycle is counted as fetch's (fetch_step): busy for a countdown or the first push
// attempt, stalled for a retried push, and a push after a stall ends that transaction
// as the cycle starts.
void Testbench::front_end_step(uint64_t t) {
  step_stage(StageId::Draw2dSetup, t, front_end_, front_end_blocked_, [&] { front_end_take(t); },
             [&](Cyc& state) { return front_end_push(t, state); });
}
// The operation batch into the op2d FIFO; true when the front end goes on in this cycle
// (it pushed after waiting for room).
bool Testbench::front_end_push(uint64_t t, Cyc& state) {
  if (!try_push(op2d_fifo_, op2d_depth_, Entry{front_end_.item, t}, front_end_blocked_, state)) return false;
  front_end_.active = false;
  const bool was_blocked = front_end_blocked_;
  front_end_blocked_ = false;
  tx_end(StageId::Draw2dSetup, was_blocked ? t : t + 1);
  return was_blocked;
}
// A testbench stage's push of `e` into `fifo` of `depth` entries: false while it is full
// (the stage blocked; a retried push's cycle is stalled).
bool Testbench::try_push(std::deque<Entry>& fifo, size_t depth, const Entry& e, bool& blocked, Cyc& state) {
  if (fifo.size() >= depth) {
    if (blocked) state = Cyc::Stalled;
    blocked = true;
    return false;
  }
  fifo.push_back(e);
  return true;
}
// One cycle of a testbench-played stage that works `left` cycles on its item and pushes
// in the last (front_end_step's comment): `take` starts the next item when idle, `push`
// makes the last cycle's push (true: the stage goes on in this cycle). The cycle is busy
// for a countdown or a first push attempt, stalled for a retried push, else starved.
template <class Take, class Push>
void Testbench::step_stage(StageId k, uint64_t t, TbStage& st, const bool& blocked, Take take, Push push) {
  Cyc state = Cyc::Starved;
  for (;;) {
    take();
    if (!st.active) break;
    last_busy_ = std::max(last_busy_, t);
    if (st.left > 1) {
      --st.left;
      state = Cyc::Busy;
      break;
    }
    if (st.left == 1 && !blocked) state = Cyc::Busy;
    if (!push(state)) break;
  }
  count(k, state);
}

// ---- The geometry front end (model/sc/front_end.cpp) ----

// The front end takes a visible clip-space job: its first step.
void Testbench::geometry_take(uint64_t t) {
  if (geometry_.active || clip_fifo_.empty() || clip_fifo_.front().pushed >= t) return;
  const TbItem& c = setup_.items[clip_fifo_.front().item];
  geometry_next_step_ = c.first_step;
  geometry_end_step_ = c.first_step + c.steps;
  geometry_ = TbStage{true, setup_.front_end_steps[c.first_step].cycles, clip_fifo_.front().item};
  clip_fifo_.pop_front();
  tx_begin(StageId::FrontEnd, t);
}
// Each step is busy its cycles and pushes its entry in the last (a step of no cycles,
// the end after the last triangle: in the cycle of the previous push), counted as the
// 2D front end's (front_end_step): busy, stalled for a retried push; after a push that
// waited, the next step or job starts in the same cycle.
void Testbench::geometry_step(uint64_t t) {
  step_stage(StageId::FrontEnd, t, geometry_, geometry_blocked_, [&] { geometry_take(t); },
             [&](Cyc& state) { return geometry_push(t, state); });
}
// The step's entry into the screen FIFO, ready front_end.latency_cycles after its first
// attempt's cycle (the model's write: ready from the cycle the work ended). True when the
// stage goes on in this cycle: a step of no cycles next, or a push that waited.
bool Testbench::geometry_push(uint64_t t, Cyc& state) {
  if (screen_fifo_.size() >= screen_depth_) {
    if (geometry_blocked_) state = Cyc::Stalled;
    else geometry_attempt_ = t;
    geometry_blocked_ = true;
    return false;
  }
  const uint64_t attempt = geometry_blocked_ ? geometry_attempt_ : t;
  const TbFrontEndStep& step = setup_.front_end_steps[geometry_next_step_];
  const uint64_t ready = attempt + 1 + setup_.timing.front_end_pipeline_latency();
  screen_fifo_.push_back(ScreenEntry{step.item, std::max(t + 1, ready)});
  const bool was_blocked = geometry_blocked_;
  geometry_blocked_ = false;
  geometry_.left = 0;
  if (++geometry_next_step_ == geometry_end_step_) {
    geometry_.active = false;
    tx_end(StageId::FrontEnd, was_blocked ? t : t + 1);
    return was_blocked;
  }
  geometry_.left = setup_.front_end_steps[geometry_next_step_].cycles;
  return was_blocked || geometry_.left == 0;
}

// ---- Front end: command fetch and primitive assembly (model/sc/command_fetch.cpp,
// prim_assembly.cpp) ----

// Assembly takes a visible command; on a clip-space command's marker, the front end's
// triangles from the screen FIFO to the command's end. Each take is a transaction, as
// the model's reads; the marker's and the end's take no cycle (transactions of none).
void Testbench::assembly_take(uint64_t t) {
  while (!assembly_.active) {
    size_t item = 0;
    if (assembly_clip_) {
      if (screen_fifo_.empty() || screen_fifo_.front().visible > t) return;
      const int64_t tri = screen_fifo_.front().item;
      screen_fifo_.pop_front();
      tx_begin(StageId::PrimAssembly, t);
      assembly_clip_ = tri >= 0;
      if (tri < 0) {
        tx_end(StageId::PrimAssembly, t);
        continue;
      }
      item = size_t(tri);
    } else {
      if (cmd_fifo_.empty() || cmd_fifo_.front().pushed >= t) return;
      item = cmd_fifo_.front().item;
      cmd_fifo_.pop_front();
      tx_begin(StageId::PrimAssembly, t);
      assembly_clip_ = setup_.items[item].kind == TbItem::ClipCommand;
      if (assembly_clip_) {
        tx_end(StageId::PrimAssembly, t);
        continue;
      }
    }
    assembly_ = TbStage{true, setup_.items[item].assembly_cost, item};
    assembly_offered_ = false;
  }
}
// Assembly counts its busy cycle and hands over on a taken offer. Its last busy cycle
// offers the triangle; later cycles of the offer are stalled, including the one in
// which a waited-for offer is taken (the SystemC write returns as that cycle starts).
void Testbench::assembly_step(uint64_t t, bool tri_taken) {
  if (!assembly_.active) {
    count(StageId::PrimAssembly, Cyc::Starved);
    return;
  }
  if (assembly_.left > 1) {
    --assembly_.left;
    count(StageId::PrimAssembly, Cyc::Busy);
    return;
  }
  const bool retry = assembly_offered_;
  assembly_offered_ = true;
  count(StageId::PrimAssembly, retry ? Cyc::Stalled : Cyc::Busy);
  if (tri_taken) {
    if (setup_.items[assembly_.item].kind == TbItem::Marker && !binner_) markers_in_flight_.push_back(assembly_.item);
    assembly_.active = false;
    tx_end(StageId::PrimAssembly, retry ? t : t + 1);
  }
}
// Fetch starts the scene's next item and pushes it into the command FIFO when done
// (a 2D command into the 2D front end's FIFO first). Like the front end: after a push
// that waited for FIFO room, the next item starts in the same cycle.
// The cycle is busy when fetch works in it (a countdown or the last cycle's first push
// attempt), stalled when it only retries a blocked push, starved otherwise (a push
// after a stall ends that transaction as the cycle starts, as the SystemC write returns).
void Testbench::fetch_step(uint64_t t) {
  Cyc state = Cyc::Starved;
  for (;;) {
    if (!fetch_.active && next_item_ < fetched_.size()) {
      const size_t item = fetched_[next_item_++];
      fetch_ = TbStage{true, setup_.items[item].fetch_cost, item};
      tx_begin(StageId::CommandFetch, t);
      if (const int64_t c = setup_.items[item].command; c >= 0 && result_.command_starts[size_t(c)] == UINT64_MAX)
        result_.command_starts[size_t(c)] = t;
    }
    if (!fetch_.active) break;
    last_busy_ = std::max(last_busy_, t);
    if (fetch_.left > 1) {
      --fetch_.left;
      state = Cyc::Busy;
      break;
    }
    if (!fetch_blocked_) state = Cyc::Busy;
    if (setup_.items[fetch_.item].kind == TbItem::Null) {
      fetch_.active = false;  // an empty primitive command: header only, nothing out
      tx_end(StageId::CommandFetch, t + 1);
      break;
    }
    if (!fetch_push(t, state)) break;
  }
  count(StageId::CommandFetch, state);
}
// Fetch's last cycle: its job into the 2D FIFO (a 2D command) or the clip-command FIFO
// (a clip-space command) once, then the item into the command FIFO. True when fetch
// goes on to its next item in this cycle (it pushed after waiting for room).
bool Testbench::fetch_push(uint64_t t, Cyc& state) {
  const TbItem& it = setup_.items[fetch_.item];
  const bool clip = it.kind == TbItem::ClipCommand;
  if ((it.work2d >= 0 || clip) && !fetch_job_pushed_) {
    if (!try_push(clip ? clip_fifo_ : draw2d_fifo_, clip ? clip_depth_ : draw2d_depth_,
                  Entry{clip ? fetch_.item : size_t(it.work2d), t}, fetch_blocked_, state))
      return false;
    fetch_job_pushed_ = true;
  }
  if (!try_push(cmd_fifo_, cmd_depth_, Entry{fetch_.item, t}, fetch_blocked_, state)) return false;
  fetch_.active = false;
  fetch_job_pushed_ = false;
  const bool was_blocked = fetch_blocked_;
  fetch_blocked_ = false;
  tx_end(StageId::CommandFetch, was_blocked ? t : t + 1);
  return was_blocked;
}

// ---- Stage statistics ----

void Testbench::count(StageId k, Cyc c) {
  StageRecord& r = record(k);
  ++(c == Cyc::Busy ? r.busy : c == Cyc::Stalled ? r.stalled : r.starved);
}
void Testbench::tx_begin(StageId k, uint64_t t) {
  meter_[stage_index(k)] = Meter{true, t};
  ++record(k).transactions;
}
void Testbench::tx_end(StageId k, uint64_t t) {
  Meter& m = meter_[stage_index(k)];
  if (!m.open) return;
  m.open = false;
  if (setup_.opts.record_transactions) record(k).spans.push_back(StageSpan{m.start, t});
}
// The RTL stages from rast_top's debug ports. No transaction: starved. Setup, coarse
// and fine raster offer an output in the last cycle of its work (busy, as the SystemC
// busy(n) before its write), the later cycles of a refused offer are stalled, and so is
// the cycle in which a waited-for output is finally taken (its work was done before;
// the SystemC write returns as that cycle starts). The interpolator's refused output
// freezes its whole pipeline, so each such cycle is stalled, and the cycle it moves
// again picks pixels (busy). The ROP likewise: busy in a cycle it works (a group's read,
// a clear's write, a marker), stalled while the memory refuses its request.
void Testbench::observe_rtl_stages(uint64_t t) {
  const RtlStageBits bits = ports_.stage_bits();
  result_.tiles_culled_hiz += uint64_t(bits.hiz_culled);
  result_.tiles_accepted_hiz += bits.hiz_accepted ? 1 : 0;
  for (size_t s = 0; s < kObservedStages.size(); ++s) {
    const StageId k = kObservedStages[s];
    if (k == StageId::Rop) {
      observe_rop(t, bits);
      continue;
    }
    const bool pipelined = k == StageId::Interpolate;
    const bool has = (bits.has >> s) & 1, done = (bits.done >> s) & 1;
    const bool blocked = has && ((bits.blocked >> s) & 1);
    const bool waited = rtl_blocked_[s];  // refused last cycle
    rtl_blocked_[s] = blocked;
    const bool stalled = pipelined ? blocked : (blocked ? waited : (has && waited));
    const bool handshake_only = has && !blocked && waited && !pipelined;
    if (has && !meter_[stage_index(k)].open) tx_begin(k, t);
    count(k, !has ? Cyc::Starved : stalled ? Cyc::Stalled : Cyc::Busy);
    if (done) tx_end(k, handshake_only ? t : t + 1);
  }
  // The texture stage: busy while it holds textured work (a fragment in its serialiser or
  // pipeline, waiting for texels included, as the SystemC stage's stall is busy), stalled
  // while the fragment FIFO refuses its output.
  count(StageId::Texture, !bits.tex_busy ? Cyc::Starved : bits.tex_blocked ? Cyc::Stalled : Cyc::Busy);
}
// The ROP: busy in a cycle it works (a group's read, a clear's write, a marker), stalled
// while the memory refuses its request, starved otherwise; or busy in the testbench's
// resolve pass. A transaction ends at its done (a batch's last write, a clear's last
// write) and starts at its start (a batch's first read taken, a marker taken), in that
// order, as one may start in the cycle another ends; a pass command (the testbench's
// command, taken with its marker) ends in its own cycle.
void Testbench::observe_rop(uint64_t t, const RtlStageBits& bits) {
  const StageId k = StageId::Rop;
  if (resolve_left_ > 0) {
    --resolve_left_;
    last_busy_ = t;
    count(k, Cyc::Busy);
    return;
  }
  const bool has = (bits.has >> kRopBit) & 1;
  count(k, !has ? Cyc::Starved : ((bits.blocked >> kRopBit) & 1) ? Cyc::Stalled : Cyc::Busy);
  if ((bits.done >> kRopBit) & 1) tx_end(k, t + 1);
  if (!bits.rop_start) return;
  if (setup_.opts.perturb_rop_cycles && record(k).transactions == setup_.opts.perturb_rop_transaction)
    perturb_now_ = setup_.opts.perturb_rop_cycles;  // test-only (CosimOptions): its first read's data later
  tx_begin(k, t);
  if (command_valid_ && command_op_ == 0 && ports_.rop_command_wanted()) tx_end(k, t + 1);
}
// The run is cycles_rtl cycles (to the ROP's last busy cycle); the loop may have
// classified a few more, in which every stage is starved: drop them.
void Testbench::close_stage_counts(uint64_t counted) {
  for (const StageInfo& s : kStages) {
    StageRecord& r = record(s.id);
    tx_end(s.id, result_.cycles_rtl);
    const uint64_t extra = counted > result_.cycles_rtl ? counted - result_.cycles_rtl : 0;
    if (r.starved < extra) {
      mismatch("stage statistics: " + std::string(s.name) + " was not starved after the last busy cycle");
      continue;
    }
    r.starved -= extra;
  }
}

// ---- Checks ----

void Testbench::mismatch(const std::string& what) {
  if (result_.first_mismatch.empty()) result_.first_mismatch = what;
  ++result_.mismatches;
}
// The early test's depth read (rtl/rast_early_z.sv): each lane's samples' stored depth
// from the memory's depth surface as the ROP's writes have left it by this cycle.
void Testbench::early_serve() {
  const uint32_t lanes = ports_.early_read_lanes();
  if (lanes == 0) return;
  const int ms = setup_.params.max_samples;
  std::vector<uint32_t> words(size_t(setup_.params.interp_fragments_per_cycle * ms), 0);
  for (int j = 0; j < setup_.params.interp_fragments_per_cycle; ++j) {
    if (!((lanes >> j) & 1)) continue;
    const auto [x, y] = ports_.early_read_pixel(j);
    if (x >= fb_.width || y >= fb_.height) continue;  // the fragment check reports it
    for (int smp = 0; smp < fb_.samples; ++smp) words[size_t(j * ms + smp)] = fb_.depth_at(x, y, smp);
  }
  ports_.drive_early_depth(words);
}
void Testbench::compare(const Fragment& f, bool culled) {
  ++result_.fragments_compared;
  if (setup_.hiz_lagged) skip_hiz_culled(f);
  if (next_expected_ >= setup_.expected.size()) {
    mismatch("extra fragment from the RTL: " + fragment_trace_line(f));
    return;
  }
  const Expected& e = setup_.expected[next_expected_++];
  if (e.hiz_tile >= 0) ++result_.hiz_lagged_fragments_drawn;
  if (e.culled != culled) {
    ++result_.command_mismatches[setup_.tri_command[size_t(e.tri)]];
    mismatch("fragment #" + std::to_string(next_expected_ - 1) + " of " + setup_.tri_names[e.tri] + ": pixel (" +
             std::to_string(e.f.x) + ", " + std::to_string(e.f.y) + ") the reference " +
             (e.culled ? "culls it early, the RTL kept it" : "keeps it, the RTL culled it early"));
  }
  if (!(e.f == f)) {
    ++result_.command_mismatches[setup_.tri_command[size_t(e.tri)]];
    mismatch("fragment #" + std::to_string(next_expected_ - 1) + " of " + setup_.tri_names[e.tri] + ": pixel (" +
             std::to_string(e.f.x) + ", " + std::to_string(e.f.y) + ") expected '" + fragment_trace_line(e.f) +
             "' mask " + std::to_string(e.f.mask) + ", RTL gave '" + fragment_trace_line(f) + "' mask " +
             std::to_string(f.mask));
  }
}
// depth.hiz_sync = lagged: the fragments of a tile the reference's Hi-Z culled are the
// RTL's to draw or not (its table lags the ROP). A tile whose first fragment is not f was
// culled by the RTL too (its run skipped); one whose first fragment is f is drawn, and the
// rest of it must follow. A tile the RTL culls and the reference does not leaves its
// fragments missing: a mismatch.
void Testbench::skip_hiz_culled(const Fragment& f) {
  const std::vector<Expected>& ex = setup_.expected;
  while (next_expected_ < ex.size()) {
    const int64_t tile = ex[next_expected_].hiz_tile;
    if (tile < 0 || tile == hiz_tile_drawn_) return;
    if (ex[next_expected_].f == f) {
      hiz_tile_drawn_ = tile;
      ++result_.hiz_lagged_tiles_drawn;
      return;
    }
    while (next_expected_ < ex.size() && ex[next_expected_].hiz_tile == tile) ++next_expected_;
  }
}
// Hi-Z's tile counts against the reference's. Lagged: the RTL culls a subset of its culls
// (each drawn one counted, but a culled tile without a covered pixel has no fragment to
// show it: hiz_culled_empty of them) and accepts at most its accepts.
void Testbench::hiz_count_check() {
  const uint64_t culled = result_.tiles_culled_hiz, accepted = result_.tiles_accepted_hiz;
  const uint64_t drawn = result_.hiz_lagged_tiles_drawn;
  const bool ok = setup_.hiz_lagged ? culled + drawn <= setup_.tiles_culled_hiz &&
                                          culled + drawn + setup_.hiz_culled_empty >= setup_.tiles_culled_hiz &&
                                          accepted <= setup_.tiles_accepted_hiz
                                    : culled == setup_.tiles_culled_hiz && accepted == setup_.tiles_accepted_hiz;
  if (!ok)
    mismatch("Hi-Z: the RTL culled " + std::to_string(culled) + " tiles (" + std::to_string(drawn) +
             " of the reference's culled drawn) and accepted " + std::to_string(accepted) + ", the reference " +
             std::to_string(setup_.tiles_culled_hiz) + " and " + std::to_string(setup_.tiles_accepted_hiz) +
             (setup_.hiz_lagged ? " (lagged: culls and accepts a subset of them)" : ""));
}
// Nothing left anywhere but the resolve pass: scene fetched, FIFOs and stages empty, the
// RTL idle (its idle_o covers the interpolator's pipeline, the fragment FIFO and the ROP)
// with no beat out, no read in flight, every command taken.
bool Testbench::done_but_rop() const {
  return next_item_ >= fetched_.size() && !fetch_.active && cmd_fifo_.empty() && !assembly_.active &&
         clip_fifo_.empty() && !geometry_.active && screen_fifo_.empty() && !assembly_clip_ &&
         ports_.idle() && !ports_.fragment_beat().valid && !read_pending_ && rop_commands_.empty() &&
         draw2d_fifo_.empty() && !front_end_.active && op2d_fifo_.empty() && engine_work_ < 0 && !engine_busy_ &&
         !rop_wait_2d_ && !rop_2d_done_ && (!binner_ || binner_->done());
}
void Testbench::end_of_run_check() {
  // Lagged: the reference-culled tiles after the RTL's last fragment were culled by it too.
  while (next_expected_ < setup_.expected.size() && setup_.expected[next_expected_].hiz_tile >= 0 &&
         setup_.expected[next_expected_].hiz_tile != hiz_tile_drawn_)
    ++next_expected_;
  if (next_expected_ < setup_.expected.size())
    mismatch(std::to_string(setup_.expected.size() - next_expected_) + " fragments missing from the RTL, first: #" +
             std::to_string(next_expected_) + " of " + setup_.tri_names[setup_.expected[next_expected_].tri] +
             ": '" + fragment_trace_line(setup_.expected[next_expected_].f) + "'");
  if (!markers_in_flight_.empty()) mismatch(std::to_string(markers_in_flight_.size()) + " markers lost in the RTL");
  for (size_t i = 0; i < depth_writes_.size(); ++i)
    if (!depth_writes_[i].empty()) {
      mismatch("depth writes of the reference missing from the RTL's ROP, first at (" +
               std::to_string(i % size_t(fb_.width)) + ", " + std::to_string(i / size_t(fb_.width)) + ")");
      break;
    }
  framebuffer_check();
}
// The whole picture: the memory's framebuffer (the ROP's writes and clears, the 2D
// engine's writes) against the reference model's. Multisampled: the resolved image (the
// reference's is resolved by render_scene).
void Testbench::framebuffer_check() {
  const Framebuffer resolved = fb_.resolve();
  result_.samples = setup_.samples;
  result_.crc_rtl = resolved.color_crc32();
  result_.crc_ref = setup_.reference.color_crc32();
  // Hi-Z (immediate mode): the depth buffer too (a table that lags the ROP must not change it).
  if (!depth_writes_.empty() && !fb_.same_depth(setup_.reference)) mismatch("the depth buffer differs from the reference's");
  for (int y = 0; y < resolved.height && result_.crc_rtl != result_.crc_ref; ++y)
    for (int x = 0; x < resolved.width; ++x)
      if (std::memcmp(resolved.pixel(x, y), setup_.reference.pixel(x, y), 3) != 0) {
        mismatch("framebuffer pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") differs from the reference");
        return;
      }
}

}  // namespace

void run_testbench(const TbSetup& setup, RastPorts& ports, CosimResult& result) {
  Testbench(setup, ports, result).run();
}

}  // namespace rastsim::rtlsim
