// SPDX-License-Identifier: Apache-2.0
#include "rtlsim/tb_rop_memory.h"

#include <algorithm>
#include <variant>

#include "ref/pipeline.h"
#include "ref/rop.h"
#include "rtlsim/testbench.h"
#include "timing/memory_timing.h"

namespace rastsim::rtlsim {

TbRopMemory::TbRopMemory(const TbSetup& s)
    : system_(s.dram), shadow_(s.arch.fb_width, s.arch.fb_height, s.samples), state_(s.arch),
      port_(system_, s.memory, shadow_, s.arch.depth_bits) {
  if (!s.opts.mem_trace_path.empty()) system_.record_trace(&trace_.emplace(s.opts.mem_trace_path).stream());
  // As simulate: the scan-out first (its requests of a cycle go first), then the ROP's
  // port (Rop::attach_memory), whose frame starts with the depth clear.
  if (s.scanout) scanout_ = attach_scanout_fetch(system_, *s.scanout, s.memory, s.arch);
  shadow_.clear_depth(static_cast<uint32_t>((uint64_t{1} << s.arch.depth_bits) - 1));
  if (s.opts.initial_fb) shadow_ = *s.opts.initial_fb;  // cosim --frames, as the testbench's memory
  if (s.binned) {  // the ROP writes the tile buffer: no ROP client (tb_binning.h has the binned clients)
    bin_stats_ = &s.binning.memory;
    return;
  }
  port_.begin(0);
  port_.functional().clear_depth();
  port_.cleared(MemClient::RopDepth);
}

uint64_t TbRopMemory::read(uint64_t t, uint32_t accesses, bool no_depth) {
  port_.begin(t);
  for (uint64_t left = accesses; left > 0;) {
    if (head_left_ == 0) {  // the next fragment's first access is in this group: all its accesses now
      if (fragments_.empty()) break;  // more accesses than fragments: the fragment check reports it
      const Fragment f = fragments_.front();
      fragments_.pop_front();
      rop_write(shadow_, f, no_depth ? DepthFunc::Always : state_.depth_func, state_.depth_write, nullptr,
                &port_.functional());
      head_left_ = TimingParams::rop_accesses(f.mask, shadow_.samples);
    }
    const uint64_t n = std::min(left, head_left_);
    left -= n;
    head_left_ -= n;
  }
  return memory_group_response(t, port_.end());
}

uint64_t TbRopMemory::operation_2d(const Draw2dWork& work, const Op2d& op, uint64_t start) {
  port_.begin(start);
  execute_op2d(shadow_, work, op, &port_.functional().color);
  return start + port_.transaction_cycles(0, start);
}

void TbRopMemory::command(const Command& cmd, uint64_t t) {
  port_.begin(t);
  apply_state_command(cmd, state_, shadow_, &port_.functional());
  if (std::holds_alternative<CmdClear>(cmd.body)) port_.cleared(MemClient::RopColor);
  if (std::holds_alternative<CmdClearDepth>(cmd.body)) port_.cleared(MemClient::RopDepth);
}

uint64_t TbRopMemory::frame_end(uint64_t t, uint64_t resolve_cycles) {
  port_.begin(t);
  port_.finish();
  frame_finished_ = true;
  return port_.transaction_cycles(resolve_cycles, t);
}

void TbRopMemory::finish(uint64_t cycles, CosimResult& r) {
  if (scanout_) scanout_->raster_done(cycles);
  if (!frame_finished_ && !bin_stats_) {
    port_.begin(cycles);
    port_.finish();
    port_.end();
  }
  system_.drain();
  if (trace_) trace_->commit();
  r.memory = bin_stats_ ? *bin_stats_ : port_.stats();
  r.dram = nlohmann::json::object();
  add_memory_system_json(r.dram, system_.report(cycles));
  if (scanout_) add_scanout_fetch_json(r.dram, scanout_->report());
}

}  // namespace rastsim::rtlsim
