// SPDX-License-Identifier: Apache-2.0
// The port adapter between the testbench (testbench.h, a plain .cpp) and one verilated config: RastPorts on a
// Vrast_<config> (rast_top) and the Vrast_engine2d beside it, one template instance per verilated config (the
// generated registry rtl_registry.cpp, and the on-demand runner rtl_runner_main.cpp). It only moves values between
// C++ and the models' ports (widths from RtlParams, Engine2dRtlParams); the testbench decides in testbench.cpp.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vrast_engine2d.h"
#include "Vrast_engine2d_rast_engine2d.h"  // its public parameters

#include "rtlsim/cosim_early_port.h"  // cosim_hiz_port.h, cosim_tile_port.h, port_bits.h, testbench.h

namespace rastsim::rtlsim {

// rast_top as class V (Vrast_<config>) and the 2D engine in one Verilator context,
// with an FST waveform of rast_top when CosimOptions::fst_path names one.
template <class V>
class VerilatedRast final : public RastPorts {
 public:
  explicit VerilatedRast(const TbSetup& s)
      : params_(s.params), engine_params_(engine2d_rtl_params()), context_(std::make_unique<VerilatedContext>()) {
    const Engine2dRtlParams built{int(Vrast_engine2d_rast_engine2d::Width), int(Vrast_engine2d_rast_engine2d::LanesMax)};
    std::string why;
    if (!engine2d_rtl_params_compatible(built, engine_params_, &why))
      throw std::runtime_error("the verilated 2D engine (rtl/rast_engine2d.sv) does not fit the testbench: " + why);
    context_->traceEverOn(!s.opts.fst_path.empty());
    top_ = std::make_unique<V>(context_.get(), "rast_top");
    engine_ = std::make_unique<Vrast_engine2d>(context_.get(), "rast_engine2d");
    if (!s.opts.fst_path.empty()) {
      waveform_ = std::make_unique<VerilatedFstC>();
      top_->trace(waveform_.get(), 99);
      waveform_->open(s.opts.fst_path.c_str());
    }
  }

  void drive_static(const TbSetup& s) override {
    top_->tile_log2_i = static_cast<uint8_t>(s.tile_log2);
    top_->fill_rule_i = static_cast<uint8_t>(s.fill_rule);
    top_->cull_mode_i = static_cast<uint8_t>(s.cull_mode);
    top_->front_ccw_i = static_cast<uint8_t>(s.front_ccw);
    top_->samples_log2_i = static_cast<uint8_t>(std::countr_zero(static_cast<unsigned>(s.samples)));
    const int w = params_.sample_off_w;
    for (int k = 0; k < params_.max_samples; ++k) {
      set_port_bits(top_->sample_dx_i, k * w, w, uint64_t(s.sample_dx[size_t(k)]));
      set_port_bits(top_->sample_dy_i, k * w, w, uint64_t(s.sample_dy[size_t(k)]));
    }
    top_->fb_width_i = static_cast<uint32_t>(s.arch.fb_width);
    top_->fb_height_i = static_cast<uint32_t>(s.arch.fb_height);
    top_->color_base_i = 0;
    top_->depth_base_i = rop_depth_base(s.arch.fb_width, s.arch.fb_height, s.samples);
    top_->depth_func_i = static_cast<uint8_t>(s.arch.depth_func);
    top_->depth_write_i = s.arch.depth_write;
    top_->tex_format_i = static_cast<uint8_t>(s.texture.format);
    top_->tex_layout_i = static_cast<uint8_t>(s.texture.layout);
    top_->tex_mem_req_ready_i = 0;
    top_->tex_mem_rsp_valid_i = 0;
    top_->tri_valid_i = 0;
    top_->cmd_valid_i = 0;
    top_->rd_ready_i = 0;
    top_->wr_ready_i = 0;
    top_->rd_rvalid_i = 0;
    top_->rst_ni = 0;
    engine_->lanes_i = static_cast<uint8_t>(s.timing.engine2d_fill_pixels_per_cycle);
    engine_->span_setup_i = static_cast<uint8_t>(s.timing.engine2d_span_setup);
    engine_->rmw_i = static_cast<uint8_t>(s.timing.engine2d_rmw);
    engine_->blit_bytes_i = static_cast<uint8_t>(s.timing.engine2d_blit_bytes_per_cycle);
    engine_->in_valid_i = 0;
    engine_->rd_ready_i = 0;
    engine_->rd_rvalid_i = 0;
    engine_->wr_ready_i = 0;
    engine_->rst_ni = 0;
  }
  void release_reset() override {
    top_->rst_ni = 1;
    engine_->rst_ni = 1;
  }
  void clock_edge(bool high) override {
    top_->clk_i = high;
    top_->eval();
    engine_->clk_i = high;
    engine_->eval();
    if (waveform_) waveform_->dump(time_);
    ++time_;
  }
  void finish() override {
    if (waveform_) waveform_->close();
    top_->final();
    engine_->final();
  }

  // The triangle port: coordinates masked to CoordW bits.
  void drive_triangle(const TbItem* it) override {
    top_->tri_valid_i = it != nullptr;
    if (!it) return;
    const uint64_t coord_mask = (uint64_t{1} << params_.coord_w) - 1;
    const auto coord = [&](int64_t v) { return static_cast<uint64_t>(v) & coord_mask; };
    top_->tri_marker_i = it->kind == TbItem::Marker;
    top_->tri_x0_i = coord(it->x[0]);
    top_->tri_y0_i = coord(it->y[0]);
    top_->tri_x1_i = coord(it->x[1]);
    top_->tri_y1_i = coord(it->y[1]);
    top_->tri_x2_i = coord(it->x[2]);
    top_->tri_y2_i = coord(it->y[2]);
    top_->tri_z0_i = it->z[0];
    top_->tri_z1_i = it->z[1];
    top_->tri_z2_i = it->z[2];
    top_->tri_rgb0_i = it->rgb[0];
    top_->tri_rgb1_i = it->rgb[1];
    top_->tri_rgb2_i = it->rgb[2];
    top_->tri_clip_x0_i = it->clip[0];
    top_->tri_clip_y0_i = it->clip[1];
    top_->tri_clip_x1_i = it->clip[2];
    top_->tri_clip_y1_i = it->clip[3];
    top_->tri_origin_x_i = it->origin[0];
    top_->tri_origin_y_i = it->origin[1];
    const int tw = params_.tex_w;
    const uint64_t tex_mask = (uint64_t{1} << tw) - 1;
    for (int v = 0; v < 3; ++v) {
      set_port_bits(top_->tri_s_i, v * tw, tw, uint64_t(int64_t(it->s[v])) & tex_mask);
      set_port_bits(top_->tri_t_i, v * tw, tw, uint64_t(int64_t(it->t[v])) & tex_mask);
      set_port_bits(top_->tri_q_i, v * 24, 24, it->q[v]);
    }
    top_->tri_affine_i = it->affine;
    top_->tri_tex_on_i = it->tex_on;
    top_->tri_tex_bilinear_i = it->tex_bilinear;
    top_->tri_tex_wrap_s_i = static_cast<uint8_t>(it->tex_wrap_s);
    top_->tri_tex_wrap_t_i = static_cast<uint8_t>(it->tex_wrap_t);
    top_->tri_tex_env_i = static_cast<uint8_t>(it->tex_env);
    top_->tri_tex_width_i = static_cast<uint16_t>(it->tex_width);
    top_->tri_tex_height_i = static_cast<uint16_t>(it->tex_height);
    top_->tri_tex_base_i = it->tex_base;
    top_->tri_tex_trilinear_i = it->tex_trilinear;
    top_->tri_tex_levels_i = static_cast<uint8_t>(it->tex_levels);
    top_->tri_tex_bias_i = static_cast<uint16_t>(uint32_t(it->tex_bias) & ((uint32_t{1} << params_.tex_bias_w) - 1));
  }
  bool triangle_ready() const override { return top_->tri_ready_o; }
  bool fragment_taken() const override { return top_->frag_ready_o; }
  FragmentBeat fragment_beat() const override {
    return {bool(top_->frag_valid_o), bool(top_->frag_marker_o), bool(top_->frag_last_o)};
  }
  bool fragment_lane_valid(int lane) const override { return port_bits(top_->frag_lanes_o, lane, 1) & 1; }
  bool fragment_lane_culled(int lane) const override { return port_bits(top_->frag_culled_o, lane, 1) & 1; }
  uint32_t early_read_lanes() const override { return early_read_lanes_of(*top_); }
  std::pair<int, int> early_read_pixel(int j) const override { return early_read_pixel_of(*top_, j, params_.pixel_w); }
  void drive_early_depth(const std::vector<uint32_t>& w) override { drive_early_depth_of(*top_, params_.depth_w, w); }
  Fragment fragment_lane(int j) const override {
    Fragment f;
    f.x = static_cast<int>(port_bits(top_->frag_x_o, j * params_.pixel_w, params_.pixel_w));
    f.y = static_cast<int>(port_bits(top_->frag_y_o, j * params_.pixel_w, params_.pixel_w));
    f.z = static_cast<uint32_t>(port_bits(top_->frag_z_o, j * params_.depth_w, params_.depth_w));
    f.r = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24, 8));
    f.g = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24 + 8, 8));
    f.b = static_cast<uint8_t>(port_bits(top_->frag_rgb_o, j * 24 + 16, 8));
    f.mask = static_cast<uint16_t>(port_bits(top_->frag_mask_o, j * params_.max_samples, params_.max_samples));
    // s, t: signed tex_w bits, sign-extended.
    const int tw = params_.tex_w;
    const auto tex = [tw](uint64_t raw) { return static_cast<int32_t>(int64_t(raw << (64 - tw)) >> (64 - tw)); };
    f.s = tex(port_bits(top_->frag_s_o, j * tw, tw));
    f.t = tex(port_bits(top_->frag_t_o, j * tw, tw));
    return f;
  }
  bool idle() const override { return top_->idle_o; }
  std::optional<uint64_t> texture_fill_request() const override {
    if (!top_->tex_mem_req_valid_o) return std::nullopt;
    return port_bits(top_->tex_mem_req_addr_o, 0, params_.tex_addr_w);
  }
  void drive_texture_fill_ready(bool ready) override { top_->tex_mem_req_ready_i = ready; }
  void drive_texture_beat(bool valid, const std::array<uint8_t, 16>& bytes) override {
    top_->tex_mem_rsp_valid_i = valid;
    set_port_bytes(top_->tex_mem_rsp_data_i, bytes);
  }
  bool texture_beat_taken() const override { return top_->tex_mem_rsp_ready_o; }
  HizRequest hiz_request() const override { return hiz_request_of(*top_); }
  void drive_hiz(uint64_t b, bool v, const std::array<uint8_t, 64>& d) override { drive_hiz_of(*top_, b, v, d); }
  TexCacheEvents texture_cache_events() const override { return {int(top_->tex_hits_o), bool(top_->tex_miss_o)}; }
  int helper_pixels() const override { return top_->tex_helpers_o; }
  RtlStageBits stage_bits() const override {
    return {top_->dbg_has_o, top_->dbg_done_o, top_->dbg_blocked_o, bool(top_->dbg_rop_start_o),
            bool(top_->dbg_tex_busy_o), bool(top_->dbg_tex_blocked_o), int(top_->dbg_hiz_culled_o), bool(top_->dbg_hiz_accepted_o)};
  }

  // ---- The ROP's command and memory ports (32-bit addresses and data words) ----
  bool rop_command_wanted() const override { return top_->cmd_ready_o; }
  void drive_rop_command(bool valid, int op, uint32_t value, const int* bin) override {
    top_->cmd_valid_i = valid;
    top_->cmd_op_i = static_cast<uint8_t>(op);
    top_->cmd_value_i = value;
    drive_bin_rect(*top_, params_, bin);
  }
  TileBeat tile_beat() const override { return tile_beat_of(*top_, params_); }
  void drive_tile(bool ready, bool rvalid, const std::vector<uint32_t>& w) override { drive_tile_of(*top_, ready, rvalid, w); }
  bool rop_read_valid() const override { return top_->rd_valid_o; }
  bool rop_read_lane_valid(int k) const override { return port_bits(top_->rd_lanes_o, k, 1) & 1; }
  bool rop_read_no_depth() const override { return top_->rd_no_depth_o; }
  RopLane rop_read_lane(int k) const override {
    const int lw = params_.rop_len_w;
    return {uint32_t(port_bits(top_->rd_addr_o, k * 32, 32)), uint32_t(port_bits(top_->rd_len_o, k * lw, lw))};
  }
  void drive_rop_memory_ready(bool read, bool write) override {
    top_->rd_ready_i = read;
    top_->wr_ready_i = write;
  }
  void drive_rop_response(bool valid, const std::vector<uint32_t>& words) override {
    top_->rd_rvalid_i = valid;
    if (!valid) return;
    for (size_t i = 0; i < words.size(); ++i) set_port_word(top_->rd_rdata_i, i, words[i]);
  }
  bool rop_write_valid() const override { return top_->wr_valid_o; }
  bool rop_write_fill() const override { return top_->wr_fill_o; }
  bool rop_write_lane_valid(int k) const override { return port_bits(top_->wr_lanes_o, k, 1) & 1; }
  RopLane rop_write_lane(int k) const override {
    const int lw = params_.rop_len_w;
    return {uint32_t(port_bits(top_->wr_addr_o, k * 32, 32)), uint32_t(port_bits(top_->wr_len_o, k * lw, lw))};
  }
  uint32_t rop_write_data(int k) const override { return uint32_t(port_bits(top_->wr_data_o, k * 32, 32)); }
  uint32_t rop_write_enables(int k, int word) const override {
    return uint32_t(port_bits(top_->wr_be_o, (k * params_.max_samples + word) * 4, 4));
  }

  // The operation port: indices masked to the engine's Width bits.
  void drive_operation(const Draw2dWork* w, const Op2d* op) override {
    engine_->in_valid_i = op != nullptr;
    if (!op) return;
    const uint32_t mask = (uint32_t{1} << engine_params_.width) - 1;
    const auto index = [&](int v) { return uint32_t(v) & mask; };
    const auto rgb = [](const std::array<uint8_t, 3>& c) { return uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16; };
    engine_->rop3_i = w->paint.rop3;
    engine_->fg_i = rgb(w->paint.fg);
    engine_->bg_i = rgb(w->paint.bg);
    uint64_t pattern = 0;  // row 0 in bits 63:56
    for (uint8_t row : w->paint.pattern.rows) pattern = pattern << 8 | row;
    engine_->pattern_i = pattern;
    engine_->pattern_solid_i = w->paint.pattern.solid;
    engine_->clip_x0_i = index(w->clip.x0);
    engine_->clip_y0_i = index(w->clip.y0);
    engine_->clip_x1_i = index(w->clip.x1);
    engine_->clip_y1_i = index(w->clip.y1);
    engine_->op_kind_i = uint8_t(op->kind);
    engine_->op_paint_i = uint8_t(op->paint);
    engine_->op_midpoint_i = op->midpoint;
    engine_->op_x0_i = index(op->x0);
    engine_->op_y0_i = index(op->y0);
    engine_->op_x1_i = index(op->x1);
    engine_->op_y1_i = index(op->y1);
    engine_->op_sx_i = index(op->sx);
    engine_->op_sy_i = index(op->sy);
    engine_->op_w_i = index(op->w);
    engine_->op_h_i = index(op->h);
  }
  bool operation_ready() const override { return engine_->in_ready_o; }
  Engine2dAccess engine_access() const override {
    const int w = engine_params_.width;
    return {signed_field(engine_->mem_x_o, w), signed_field(engine_->mem_y_o, w), signed_field(engine_->mem_sx_o, w),
            signed_field(engine_->mem_sy_o, w)};
  }
  Engine2dRead engine_read() const override {
    return {bool(engine_->rd_valid_o), uint32_t(engine_->rd_lanes_o), bool(engine_->rd_src_o)};
  }
  void drive_engine_read(bool ready, bool rvalid, const std::vector<uint32_t>& d, uint32_t s) override {
    engine_->rd_ready_i = ready;
    engine_->rd_rvalid_i = rvalid;
    for (size_t k = 0; k < d.size(); ++k) set_port_bits(engine_->rd_d_i, int(k) * 24, 24, d[k]);
    engine_->rd_s_i = s;
    engine_->eval();
  }
  Engine2dWrite engine_write() const override {
    return {bool(engine_->wr_valid_o), bool(engine_->wr_last_o), uint32_t(engine_->wr_be_o)};
  }
  void drive_engine_write_ready(bool ready) override {
    engine_->wr_ready_i = ready;
    engine_->eval();
  }
  uint32_t engine_write_rgb(int lane) const override {
    return static_cast<uint32_t>(port_bits(engine_->wr_data_o, lane * 24, 24));
  }

 private:
  const RtlParams& params_;
  const Engine2dRtlParams& engine_params_;
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<V> top_;
  std::unique_ptr<Vrast_engine2d> engine_;
  std::unique_ptr<VerilatedFstC> waveform_;
  uint64_t time_ = 0;  // half cycles, the waveform's time
};

template <class V>
void run_rtl(const TbSetup& s, CosimResult& r) {
  VerilatedRast<V> ports(s);
  run_testbench(s, ports, r);
}

}  // namespace rastsim::rtlsim
