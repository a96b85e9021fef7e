// SPDX-License-Identifier: Apache-2.0
#include "config/timing_params.h"

#include <cstdlib>

#include "ref/2d/rop3.h"

namespace rastsim {

TimingParams TimingParams::from_config(const Config& cfg) {
  TimingParams p;
  auto u = [&](const char* key) { return static_cast<uint64_t>(cfg.get_int(key)); };
  auto depth = [&](const char* key) { return static_cast<int>(cfg.get_int(key)); };
  p.core_mhz = cfg.get_float("clock.core_mhz");
  p.fetch_cycles_per_command = u("fetch.cycles_per_command");
  p.fetch_vertices_per_cycle = u("fetch.vertices_per_cycle");
  p.front_end_cycles_per_primitive = u("front_end.cycles_per_primitive");
  p.front_end_clip_cycles_per_vertex = u("front_end.clip_cycles_per_vertex");
  p.front_end_vertices_per_cycle = u("front_end.vertices_per_cycle");
  p.front_end_latency = u("front_end.latency_cycles");
  p.assembly_cycles_per_triangle = u("assembly.cycles_per_triangle");
  p.setup_interval = u("setup.interval_cycles");
  p.setup_latency = u("setup.latency_cycles");
  p.coarse_tiles_per_cycle = u("coarse.tiles_per_cycle");
  p.fine_samples_per_cycle = u("fine.samples_per_cycle");
  p.fine_accepted_tile_cycles = u("fine.accepted_tile_cycles");
  p.coarse_scanline_setup = u("coarse.scanline_setup_cycles");
  p.fine_span_setup = u("fine.span_setup_cycles");
  p.fine_span_pixels_per_cycle = u("fine.span_pixels_per_cycle");
  p.interp_fragments_per_cycle = u("interp.fragments_per_cycle");
  p.interp_latency = u("interp.latency_cycles");
  p.interp_perspective = cfg.get_bool("interp.perspective");
  p.recip_iterations = u("interp.recip_iterations");
  p.recip_lanes = u("recip.lanes");
  p.rop_pixels_per_cycle = u("rop.pixels_per_cycle");
  p.rop_clear_pixels_per_cycle = u("rop.clear_pixels_per_cycle");
  p.rop_resolve_bytes_per_cycle = u("rop.resolve_bytes_per_cycle");
  p.setup2d_ops_per_cycle = u("setup2d.ops_per_cycle");
  p.engine2d_fill_pixels_per_cycle = u("engine2d.fill_pixels_per_cycle");
  p.engine2d_span_setup = u("engine2d.span_setup_cycles");
  p.engine2d_rmw = u("engine2d.rmw_cycles");
  p.engine2d_blit_bytes_per_cycle = u("engine2d.blit_bytes_per_cycle");
  p.fifo_draw2d = depth("fifo.draw2d_depth");
  p.fifo_op2d = depth("fifo.op2d_depth");
  p.fifo_command = depth("fifo.command_depth");
  p.fifo_clip_command = depth("fifo.clip_command_depth");
  p.fifo_screen = depth("fifo.screen_depth");
  p.fifo_triangle = depth("fifo.triangle_depth");
  p.fifo_setup = depth("fifo.setup_depth");
  p.fifo_tile = depth("fifo.tile_depth");
  p.fifo_pixel = depth("fifo.pixel_depth");
  p.fifo_fragment = depth("fifo.fragment_depth");
  p.fifo_texture = depth("fifo.texture_depth");
  p.texture_quads_per_cycle = u("texture.quads_per_cycle");
  p.texture_bilinear_per_cycle = u("texture.bilinear_per_cycle");
  p.texture_texels_per_cycle = u("texture.texels_per_cycle");
  p.texture_combine_per_cycle = u("texture.combine_per_cycle");
  p.texture_miss_cycles = u("texture.miss_cycles");
  p.texture_latency = u("texture.latency_cycles");
  if (p.setup_latency < p.setup_interval)
    throw ConfigError(cfg.origin("setup.latency_cycles") + ": setup.latency_cycles = " +
                      std::to_string(p.setup_latency) + " is less than setup.interval_cycles = " +
                      std::to_string(p.setup_interval) + " (" + cfg.origin("setup.interval_cycles") +
                      "); a pipelined stage cannot finish a triangle before accepting the next");
  return p;
}

uint64_t TimingParams::stage_pass_cycles(StagePass pass) const {
  switch (pass) {
    case StagePass::FetchHeader: return fetch_cycles_per_command;
    case StagePass::IssueCycle: return state_pass_cycles();  // every cost is >= 1 cycle (schema minimums)
    case StagePass::IssueSetupLatency: return state_pass_cycles() + setup_pipeline_latency();
    case StagePass::IssueInterpLatency: return state_pass_cycles() + interp_pipeline_latency();
    case StagePass::IssueFrontEndLatency: return state_pass_cycles() + front_end_pipeline_latency();
  }
  return 0;
}

uint64_t TimingParams::stage_fill_cycles(StageId stage) const {
  const StageInfo& s = stage_info(stage);
  if (s.fed_by == stage) return 0;  // the first stage
  return stage_fill_cycles(s.fed_by) + stage_pass_cycles(stage_info(s.fed_by).pass);
}

int TimingParams::fifo_entries(FifoId fifo) const {
  switch (fifo) {
    case FifoId::Command: return fifo_command;
    case FifoId::ClipCommand: return fifo_clip_command;
    case FifoId::Screen: return screen_fifo_entries();
    case FifoId::Triangle: return fifo_triangle;
    case FifoId::Setup: return setup_fifo_entries();
    case FifoId::Tile: return fifo_tile;
    case FifoId::Pixel: return fifo_pixel;
    case FifoId::Fragment: return fragment_fifo_entries();
    case FifoId::Texture: return texture_fifo_entries();
    case FifoId::Draw2d: return fifo_draw2d;
    case FifoId::Op2d: return fifo_op2d;
    case FifoId::Grant2d:
    case FifoId::Done2d:
    case FifoId::TextureDone: return 1;
  }
  return 0;
}

uint64_t TimingParams::engine2d_op_cycles(const Op2d& op, uint8_t rop3) const {
  const bool reads_d = rop3_reads_destination(rop3);
  switch (op.kind) {
    case Op2d::Kind::Span: return engine2d_span_cycles(uint64_t(op.x1 - op.x0), reads_d);
    case Op2d::Kind::Pixel: return engine2d_pixel_cycles(reads_d);
    case Op2d::Kind::Line: {
      const int64_t dx = std::abs(int64_t(op.x1) - op.x0), dy = std::abs(int64_t(op.y1) - op.y0);
      return engine2d_line_cycles(uint64_t(std::max(dx, dy)) + 1, reads_d);
    }
    case Op2d::Kind::Blit:
      return engine2d_blit_cycles(uint64_t(op.w), uint64_t(op.h), rop3_reads_source(rop3), reads_d);
  }
  return 0;
}

}  // namespace rastsim
