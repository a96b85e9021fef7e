// SPDX-License-Identifier: Apache-2.0
#include "sc/raster_pipeline.h"
#include "report/stats_json.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <utility>
#include <vector>

#include <systemc>

#include "ref/hiz.h"
#include "sc/binning.h"
#include "sc/model_error.h"
#include "sc/rop.h"
#include "sc/texture.h"
#include "scene/scene_io.h"
#include "util/atomic_file.h"

namespace rastsim::sc {

namespace {

// The top module: FIFOs first (stages hold references to them), then the stages. Both
// lists are timing/stage_table.h's: each channel and module takes its name and depth from
// its row, and stage() / visit_fifo() map every row to its member (a row without one
// stops the build: -Wswitch).
struct RasterPipeline : sc_core::sc_module {
  RasterPipeline(sc_core::sc_module_name name, SimContext& ctx, CommandSource source, const RasterState& arch,
                 const TimingParams& p)
      : sc_module(name),
        command_fifo(fifo_name(FifoId::Command).data(), p.fifo_entries(FifoId::Command), ctx.tracing, ctx.wake_writers_at_free_slot),
        clip_command_fifo(fifo_name(FifoId::ClipCommand).data(), p.fifo_entries(FifoId::ClipCommand), ctx.tracing,
                          ctx.wake_writers_at_free_slot),
        screen_fifo(fifo_name(FifoId::Screen).data(), p.fifo_entries(FifoId::Screen), ctx.tracing, ctx.wake_writers_at_free_slot),
        triangle_fifo(fifo_name(FifoId::Triangle).data(), p.fifo_entries(FifoId::Triangle), ctx.tracing, ctx.wake_writers_at_free_slot),
        setup_fifo(fifo_name(FifoId::Setup).data(), p.fifo_entries(FifoId::Setup), ctx.tracing, ctx.wake_writers_at_free_slot),
        bin_fifo("bin_fifo", p.fifo_entries(FifoId::Setup), ctx.tracing, ctx.wake_writers_at_free_slot),
        tile_fifo(fifo_name(FifoId::Tile).data(), p.fifo_entries(FifoId::Tile), ctx.tracing, ctx.wake_writers_at_free_slot),
        pixel_fifo(fifo_name(FifoId::Pixel).data(), p.fifo_entries(FifoId::Pixel), ctx.tracing, ctx.wake_writers_at_free_slot),
        fragment_fifo(fifo_name(FifoId::Fragment).data(), p.fifo_entries(FifoId::Fragment), ctx.tracing, ctx.wake_writers_at_free_slot),
        texture_fifo(fifo_name(FifoId::Texture).data(), p.fifo_entries(FifoId::Texture), ctx.tracing, ctx.wake_writers_at_free_slot),
        texture_done(fifo_name(FifoId::TextureDone).data(), p.fifo_entries(FifoId::TextureDone), ctx.tracing,
                     ctx.wake_writers_at_free_slot),
        draw2d_fifo(fifo_name(FifoId::Draw2d).data(), p.fifo_entries(FifoId::Draw2d), ctx.tracing, ctx.wake_writers_at_free_slot),
        op2d_fifo(fifo_name(FifoId::Op2d).data(), p.fifo_entries(FifoId::Op2d), ctx.tracing, ctx.wake_writers_at_free_slot),
        grant_2d(fifo_name(FifoId::Grant2d).data(), p.fifo_entries(FifoId::Grant2d), ctx.tracing, ctx.wake_writers_at_free_slot),
        done_2d(fifo_name(FifoId::Done2d).data(), p.fifo_entries(FifoId::Done2d), ctx.tracing, ctx.wake_writers_at_free_slot),
        command_fetch(ctx, std::move(source), arch, p, command_fifo, clip_command_fifo, draw2d_fifo),
        front_end(ctx, p, clip_command_fifo, screen_fifo),
        prim_assembly(ctx, p, command_fifo, screen_fifo, triangle_fifo),
        tri_setup(ctx, arch, p, triangle_fifo, setup_fifo),
        coarse_raster(ctx, arch, p, arch.bin.mode == PipelineMode::Binned ? bin_fifo : setup_fifo, tile_fifo),
        fine_raster(ctx, arch, p, tile_fifo, pixel_fifo),
        interpolate(ctx, arch, p, pixel_fifo, fragment_fifo, texture_fifo, texture_done),
        texture(ctx, arch, p, texture_fifo, fragment_fifo, texture_done),
        rop(ctx, arch, p, fragment_fifo, grant_2d, done_2d),
        draw2d_setup(ctx, p, draw2d_fifo, op2d_fifo),
        engine2d(ctx, p, rop.framebuffer(), op2d_fifo, grant_2d, done_2d) {}

  Link<CommandItem> command_fifo;
  Link<ClipCommandItem> clip_command_fifo;
  Link<ScreenItem> screen_fifo;
  Link<TriangleItem> triangle_fifo;
  Link<SetupItem> setup_fifo;
  // pipeline.mode = binned: binner -> coarse raster (setup_fifo then feeds the binner;
  // sc/binning.h). Outside the table: unused, and unreported, in immediate mode.
  Link<SetupItem> bin_fifo;
  Link<TileItem> tile_fifo;
  Link<PixelItem> pixel_fifo;
  Link<FragmentItem> fragment_fifo;
  Link<FragmentItem> texture_fifo;
  Link<TextureFence> texture_done;
  Link<Draw2dItem> draw2d_fifo;
  Link<Op2dItem> op2d_fifo;
  Link<PortGrant> grant_2d, done_2d;  // the ROP's framebuffer port, lent to the 2D engine
  CommandFetch command_fetch;
  FrontEnd front_end;
  PrimAssembly prim_assembly;
  TriSetup tri_setup;
  CoarseRaster coarse_raster;
  FineRaster fine_raster;
  Interpolate interpolate;
  Texture texture;
  Rop rop;
  Draw2dSetup draw2d_setup;
  Engine2d engine2d;

  Stage& stage(StageId id) {
    switch (id) {
      case StageId::CommandFetch: return command_fetch;
      case StageId::FrontEnd: return front_end;
      case StageId::PrimAssembly: return prim_assembly;
      case StageId::TriSetup: return tri_setup;
      case StageId::CoarseRaster: return coarse_raster;
      case StageId::FineRaster: return fine_raster;
      case StageId::Interpolate: return interpolate;
      case StageId::Texture: return texture;
      case StageId::Rop: return rop;
      case StageId::Draw2dSetup: return draw2d_setup;
      case StageId::Engine2d: return engine2d;
    }
    throw std::logic_error("RasterPipeline::stage: not a stage");
  }
  template <class F>
  void visit_fifo(FifoId id, F&& f) {
    switch (id) {
      case FifoId::Command: return f(command_fifo);
      case FifoId::ClipCommand: return f(clip_command_fifo);
      case FifoId::Screen: return f(screen_fifo);
      case FifoId::Triangle: return f(triangle_fifo);
      case FifoId::Setup: return f(setup_fifo);
      case FifoId::Tile: return f(tile_fifo);
      case FifoId::Pixel: return f(pixel_fifo);
      case FifoId::Fragment: return f(fragment_fifo);
      case FifoId::Texture: return f(texture_fifo);
      case FifoId::TextureDone: return f(texture_done);
      case FifoId::Draw2d: return f(draw2d_fifo);
      case FifoId::Op2d: return f(op2d_fifo);
      case FifoId::Grant2d: return f(grant_2d);
      case FifoId::Done2d: return f(done_2d);
    }
  }

  // Every stage in table order: the triangle path in pipeline order, then the 2D path.
  std::array<Stage*, kStageCount> stages() {
    std::array<Stage*, kStageCount> all{};
    for (const StageInfo& s : kStages) all[stage_index(s.id)] = &stage(s.id);
    return all;
  }
  template <class F>
  void for_each_fifo(F&& f) {
    for (const FifoInfo& l : kFifos) visit_fifo(l.id, f);
  }
};

std::string strip_suffix(std::string path, const std::string& suffix) {
  if (path.size() > suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0)
    path.resize(path.size() - suffix.size());
  return path;
}

}  // namespace

// Passing every stage of the triangle path: fetch's header, one issue cycle in each later
// stage, and the pipeline latencies of setup and interpolation, which every transaction
// (state markers too) waits.
uint64_t fixed_latency_cycles(const TimingParams& p) {
  const StageId last = last_triangle_stage();
  return p.stage_fill_cycles(last) + p.stage_pass_cycles(stage_info(last).pass);
}

SimResult simulate_scene(const Scene& scene, const ArchParams& arch, const SimOptions& opts) {
  return simulate_commands(scene_source(scene), arch, opts);
}

SimResult simulate_stream(const std::string& path, const ArchParams& arch, const SimOptions& opts, size_t batch) {
  // The reader runs on a thread of its own, kSceneBatchesAhead batches ahead of command
  // fetch (the model itself stays one SystemC thread; memory stays bounded by those
  // batches). It starts here, so the first batch is parsed while the pipeline elaborates.
  SceneAhead reader(path, arch.placement, batch, kSceneBatchesAhead);
  auto source = [&](const CommandTake& take) {
    uint64_t fetched = 0;
    bool fetching = false;  // an error of the pipeline itself, not of the reader, passes unchanged
    try {
      std::vector<Command> b;
      while (reader.next(b)) {
        // The batch moves into one shared block; each command's pointer shares it.
        const LocalPtr<const std::vector<Command>> owner = make_local<std::vector<Command>>(std::move(b));
        b = {};
        for (const Command& c : *owner) {
          fetching = true;
          take(CommandPtr(owner, &c));
          fetching = false;
          ++fetched;
        }
      }
    } catch (const SceneError& e) {
      if (fetching || fetched == 0) throw;
      throw SceneError(std::string(e.what()) + " (after " + std::to_string(fetched) +
                       " commands of the scene were fetched, at cycle " +
                       std::to_string(Stage::current_cycle()) +
                       " of the simulation; no image or stats written)");
    }
  };
  return simulate_commands(source, arch, opts);
}

namespace {

// The optional recorders of a run (timeline, spans, tile heat, VCD), attached to the
// stages and FIFOs before the simulation starts. The VCD is written at a temporary name
// (util/atomic_file.h), renamed into place by commit() after a successful run, removed
// otherwise.
struct Recorders {
  Timeline timeline;
  std::vector<std::vector<Span>> spans = std::vector<std::vector<Span>>(kStageCount);
  std::vector<TileHeat> heat;
  sc_core::sc_trace_file* vcd = nullptr;
  std::unique_ptr<PendingFile> vcd_file;

  void attach(RasterPipeline& top, const SimOptions& opts, const RasterState& arch, bool tracing) {
    if (!opts.timeline_path.empty()) {
      for (Stage* s : top.stages()) s->set_timeline(&timeline.add_stage(s->basename()));
      top.for_each_fifo([&](auto& f) { f.set_timeline(&timeline.add_fifo(f.basename(), f.depth())); });
    }
    if (opts.spans)
      for (size_t k = 0; k < spans.size(); ++k) top.stages()[k]->set_spans(&spans[k]);
    if (opts.heatmap) {
      heat.reserve(kStageCount);  // the stages keep pointers into it
      for (const StageInfo& info : kStages)
        if (info.tile_heat)
          top.stage(info.id).set_heat(
              &heat.emplace_back(std::string(info.name), arch.fb_width, arch.fb_height, arch.tile_size));
    }
    if (tracing) {
      // SystemC appends ".vcd" to the name it is given.
      vcd_file = std::make_unique<PendingFile>(strip_suffix(opts.vcd_path, ".vcd") + ".vcd");
      vcd = sc_core::sc_create_vcd_trace_file(strip_suffix(vcd_file->path(), ".vcd").c_str());
      vcd->set_time_unit(1, sc_core::SC_NS);  // 1 ns = 1 cycle
      for (Stage* s : top.stages()) sc_core::sc_trace(vcd, s->state_signal(), std::string(s->basename()) + ".state");
      top.for_each_fifo(
          [&](auto& f) { sc_core::sc_trace(vcd, f.occupancy(), std::string(f.basename()) + ".occupancy"); });
    }
  }
};

// The run's options into the context the stages share (which stays where it is: stages
// compare commands against its end-of-frame marker's address).
void configure(SimContext& ctx, const SimOptions& opts, const RasterState& arch) {
  ctx.tracing = !opts.vcd_path.empty();
  ctx.lockstep = ctx.tracing || !opts.timeline_path.empty() || opts.lockstep;
  ctx.stall_seed = opts.stall_seed;
  ctx.stall_probability = opts.stall_probability;
  ctx.on_fragment = opts.on_fragment;
  ctx.on_fetch = opts.on_fetch;
  ctx.on_rop_state = opts.on_rop_state;
  ctx.on_hiz = opts.on_hiz;
  ctx.hiz_lag_accept_busy = opts.hiz_lag_accept_busy;
  count_multisample_footprint(arch, ctx.render);
  ctx.render.depth_early = arch.depth_early;  // its stats keys, as the reference's
  // Binned mode has two memory clients in different processes, the binner (parameter
  // buffer) and the ROP (tile loads and stores): their requests enter in time order
  // (docs/binning.md, "Timed model").
  // A writer woken late (sc/link.h) would make its requests out of time order: the binner
  // blocked on its output would issue its next bin's prefetch after SystemC time passed it.
  ctx.memory_time_order = arch.bin.mode == PipelineMode::Binned;
  ctx.wake_writers_at_free_slot = ctx.lockstep || ctx.memory_time_order;
}

// The run ends with the last stage's last step, or the Hi-Z flush engine's idle cycle if
// later: the latest of their times (in lock-step, where SystemC time followed them, also
// SystemC's; sc/stage.h).
uint64_t end_cycle(RasterPipeline& top, const SimContext& ctx) {
  uint64_t end = top.coarse_raster.hiz_flush_end();
  for (Stage* s : top.stages()) end = std::max(end, s->now());
  if (ctx.lockstep && end != ctx.to_cycles(sc_core::sc_time_stamp()))
    throw ModelError("simulate: the stages end at cycle " + std::to_string(end) + " but SystemC at cycle " +
                     std::to_string(ctx.to_cycles(sc_core::sc_time_stamp())));
  return end;
}

// Every stage's and FIFO's figures at cycle r.cycles, and the lower bound they give.
void collect_stages(RasterPipeline& top, const TimingParams& p, Recorders& rec, SimResult& r) {
  for (const StageInfo& info : kStages) {
    Stage& s = top.stage(info.id);
    s.finish(r.cycles);
    const StageStats& st = s.stats();
    r.stages.push_back({s.basename(), st.busy, st.stalled, st.starved, st.transactions_in, st.transactions_out,
                        std::move(rec.spans[stage_index(info.id)]), st.transactions()});
    // A stage with work starts no earlier than its fill (TimingParams::stage_fill_cycles).
    if (st.busy > 0) r.cycles_lower_bound = std::max(r.cycles_lower_bound, p.stage_fill_cycles(info.id) + st.busy);
  }
  top.for_each_fifo([&](auto& f) {
    r.fifos.push_back({f.basename(), f.depth(), f.writes(), f.reads()});
    if (f.writes() != f.reads())
      throw ModelError(std::string(f.name()) + ": " + std::to_string(f.writes() - f.reads()) +
                       " transactions left behind (pipeline deadlock)");
  });
}

// The binner's figures (outside the stage table: stages.binner, fifos.bin_fifo).
void collect_binner(BinnerStage& b, Link<SetupItem>& fifo, SimResult& r) {
  b.finish(r.cycles);
  const StageStats& st = b.stats();
  r.binner = StageReport{b.basename(), st.busy, st.stalled, st.starved, st.transactions_in, st.transactions_out,
                         {}, st.transactions()};
  r.bin_fifo = FifoReport{fifo.basename(), fifo.depth(), fifo.writes(), fifo.reads()};
  r.cycles_lower_bound = std::max(r.cycles_lower_bound, st.busy);
  if (fifo.writes() != fifo.reads())
    throw ModelError(std::string(fifo.name()) + ": " + std::to_string(fifo.writes() - fifo.reads()) +
                     " transactions left behind (pipeline deadlock)");
}

// Requests of one cycle enter the DRAM in this order, each rank one SystemC delta after
// the one before, from the processes SystemC time woke (which process runs first
// otherwise differs between a decoupled and a lock-step run): 0 the Hi-Z tests' reads and
// the binner's, 1 the Hi-Z flush engine's (its own delta, sc/hiz_flush.h), 2 the ROP's
// (tile loads and stores binned), 3 the texture stage's. The RTL testbench's order within
// a cycle: rast_hiz_spill's port serves the tests before the engine, the testbench the
// Hi-Z port and the binner before the ROP; the texture after the ROP as the cosims agree
// (textured_mip_cosim dram 29,104 cycles against the RTL's 29,105).
int equal_cycle_rank(MemClient c) {
  switch (c) {
    case MemClient::Texture: return 3;
    case MemClient::RopColor:
    case MemClient::RopDepth:
    case MemClient::TileStore: return 2;
    case MemClient::Hiz:
    case MemClient::Binning:
    case MemClient::Scanout: return 0;
  }
  return 0;
}

// The clients of the shared memory system (memory.model = "dram"), after the scan-out's
// fetch (its requests at cycle 0 go first): in binned mode the binner's binning and
// tile_store clients (no ROP, 2D, texture or Hi-Z client), else the ROP (its first request
// the frame's depth clear, cold unless warmed), the 2D engine through the ROP's colour
// client, the texture cache's line fills and the spilled Hi-Z table's entries. Textured
// runs put every request in at its own cycle (time order).
void attach_memory_clients(MemorySystem& memory, RasterPipeline& top, BinnerStage* binner, const ArchParams& params,
                           const SimOptions& opts, SimContext& ctx) {
  if (binner) {
    binner->attach_memory(memory);
  } else {
    top.rop.attach_memory(memory, params.memory, opts.warm_memory);
    top.engine2d.attach_memory(top.rop.memory_port());
    top.texture.attach_memory(memory);
    top.coarse_raster.attach_memory(memory);
  }
  // A process waits its rank once a cycle: its further requests of the cycle follow at
  // once, before a higher rank's (ranked each, the ROP's second request of a cycle went
  // after the texture stage's first).
  using Ranked = std::vector<std::pair<const sc_core::sc_object*, uint64_t>>;  // process, cycle
  memory.set_arrival_wait([&ctx, ranked = Ranked{}](uint64_t cycle, MemClient c) mutable {
    if (!ctx.memory_time_order) return;
    const uint64_t now = ctx.to_cycles(sc_core::sc_time_stamp());
    if (cycle > now) sc_core::wait(double(cycle - now) * ctx.cycle);
    if (cycle < now) return;
    const sc_core::sc_object* p = sc_core::sc_get_current_process_handle().get_process_object();
    auto it = std::find_if(ranked.begin(), ranked.end(), [p](const auto& r) { return r.first == p; });
    if (it == ranked.end()) it = ranked.insert(ranked.end(), {p, cycle + 1});
    if (it->second == cycle) return;
    it->second = cycle;
    for (int k = equal_cycle_rank(c); k > 0; --k) sc_core::wait(sc_core::SC_ZERO_TIME);
  });
}

// The memory figures at the frame's end: the scan-out told the raster is done, the
// clients' last accesses made, every request completed, then each report.
void collect_memory(MemorySystem& memory, ScanoutFetch* scanout, RasterPipeline& top, BinnerStage* binner,
                    SimResult& r) {
  if (scanout) scanout->raster_done(r.cycles);
  r.render.memory = binner ? binner->memory_stats() : top.rop.finish_memory(r.cycles);
  memory.drain();
  r.memory = memory.report(r.cycles);
  if (scanout) r.scanout = scanout->report();
  if (const TextureMemoryPort* t = top.texture.memory_port(); t && t->report().reads > 0)
    r.texture_memory = t->report();
  if (const HizMemoryPort* h = top.coarse_raster.memory_port(); h && h->report().reads + h->report().writes > 0)
    r.hiz_memory = h->report();
}

}  // namespace

SimResult simulate_commands(CommandSource source, const ArchParams& params, const SimOptions& opts) {
  const auto t0 = std::chrono::steady_clock::now();
  const RasterState& arch = params.raster;
  const TimingParams& p = params.timing;

  setenv("SC_COPYRIGHT_MESSAGE", "DISABLE", 1);  // before the simulation context exists
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);

  const bool binned = arch.bin.mode == PipelineMode::Binned;
  if (binned && (arch.depth_early || hiz_applies(arch)))
    throw std::invalid_argument("pipeline.mode = binned with depth.early or depth.hiz: the SystemC level does not "
                                "model early or hierarchical Z in the tile buffer yet; `rastsim render` draws it "
                                "(docs/binning.md, \"Not yet\")");
  SimContext ctx;
  configure(ctx, opts, arch);
  // Built once and kept: SystemC does not support tearing a design down.
  static RasterPipeline* top = nullptr;
  if (top) throw std::logic_error("simulate_scene: SystemC elaborates only once per process");
  top = new RasterPipeline("pipeline", ctx, std::move(source), arch, p);
  if (opts.initial_fb) top->rop.framebuffer() = *opts.initial_fb;  // engine2d holds the same object
  top->interpolate.start_early_depth(top->rop.framebuffer());         // depth.early: the same start
  static BinnerStage* binner = nullptr;  // pipeline.mode = binned (sc/binning.h), kept as the top
  if (binned) {
    binner = new BinnerStage(ctx, arch, p, params.memory.enabled ? &params.memory : nullptr, top->setup_fifo,
                             top->bin_fifo);
    top->tri_setup.log_commands(&binner->commands());
    top->rop.attach_bins(binner->rop_port());
  }
  Recorders rec;
  rec.attach(*top, opts, arch, ctx.tracing);
  static MemorySystem* memory = nullptr;  // kept, as the top: elaborated once
  static ScanoutFetch* scanout = nullptr;
  std::optional<AtomicFile> mem_trace;
  if (params.memory.enabled) {
    memory = new MemorySystem(params.dram);
    if (!opts.mem_trace_path.empty()) memory->record_trace(&mem_trace.emplace(opts.mem_trace_path).stream());
    scanout = attach_scanout_fetch(*memory, params, opts.scanout_phase).release();  // first: its requests at cycle 0 go first
    attach_memory_clients(*memory, *top, binned ? binner : nullptr, params, opts, ctx);
    if (opts.on_memory_system) opts.on_memory_system(*memory);
  } else if (!opts.mem_trace_path.empty()) {
    throw std::invalid_argument("--mem-trace needs memory.model = \"dram\" (the DRAM requests it lists)");
  }

  sc_core::sc_start();
  if (memory) memory->set_arrival_wait({});  // the frame end's requests come after every stage's
  if (rec.vcd) sc_core::sc_close_vcd_trace_file(rec.vcd);
  ctx.rethrow_failure();  // SceneError for bad input, ModelError for a fault of the model

  SimResult r;
  r.core_mhz = p.core_mhz;
  r.cycles = end_cycle(*top, ctx);
  if (binner) r.cycles = std::max(r.cycles, binner->now());
  collect_stages(*top, p, rec, r);
  if (binner) collect_binner(*binner, top->bin_fifo, r);
  if (!opts.timeline_path.empty())
    r.timeline = rec.timeline.write_trace_json(opts.timeline_path, r.cycles, opts.timeline_max_events);
  r.heat = std::move(rec.heat);
  top->coarse_raster.finish_coverage();
  top->coarse_raster.finish_hiz();
  top->texture.finish_texture();
  r.render = ctx.render;
  r.rop_accesses = ctx.rop_accesses;
  r.framebuffer_bytes = ctx.framebuffer_bytes;
  r.resolve_cycles = ctx.resolve_cycles;
  r.recip_reciprocals = ctx.recip_reciprocals;
  r.recip_busy_cycles = ctx.recip_busy_cycles;
  if (memory) {  // the frame end's accesses, then every request completed
    collect_memory(*memory, scanout, *top, binner, r);
    if (mem_trace) mem_trace->commit();
  }
  r.fb = std::move(top->rop.framebuffer());  // moved, not copied: one framebuffer
  r.render.framebuffer_crc32 = r.fb.color_crc32();
  r.sim_wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.render.wall_seconds = r.sim_wall_seconds;
  if (rec.vcd_file) rec.vcd_file->commit();
  return r;
}

nlohmann::json SimResult::to_json() const {
  nlohmann::json j = rastsim::to_json(render);
  j["cycles"] = cycles;
  j["cycles_lower_bound"] = cycles_lower_bound;
  j["core_mhz"] = core_mhz;
  j["simulated_seconds"] = double(cycles) / (core_mhz * 1e6);
  j["sim_wall_seconds"] = sim_wall_seconds;
  j["simulated_cycles_per_second"] = sim_wall_seconds > 0 ? double(cycles) / sim_wall_seconds : 0.0;
  j["rop_accesses"] = rop_accesses;
  j["framebuffer_bytes"] = framebuffer_bytes;
  j["resolve_cycles"] = resolve_cycles;
  j["recip_reciprocals"] = recip_reciprocals;
  j["recip_busy_cycles"] = recip_busy_cycles;
  for (const StageReport& s : stages)
    j["stages"][s.name] = {{"busy", s.busy},
                           {"stalled", s.stalled},
                           {"starved", s.starved},
                           {"transactions_in", s.transactions_in},
                           {"transactions_out", s.transactions_out}};
  for (const FifoReport& f : fifos) j["fifos"][f.name] = {{"depth", f.depth}, {"transactions", f.writes}};
  if (binner)
    j["stages"][binner->name] = {{"busy", binner->busy},
                                 {"stalled", binner->stalled},
                                 {"starved", binner->starved},
                                 {"transactions_in", binner->transactions_in},
                                 {"transactions_out", binner->transactions_out}};
  if (bin_fifo) j["fifos"][bin_fifo->name] = {{"depth", bin_fifo->depth}, {"transactions", bin_fifo->writes}};
  if (memory) add_memory_system_json(j, *memory);
  if (scanout) add_scanout_fetch_json(j, *scanout);
  if (texture_memory) add_texture_memory_json(j, *texture_memory);
  if (hiz_memory) add_hiz_memory_json(j, *hiz_memory);
  // The geometry front end's counters under its stage too, beside its cycles.
  if (render.front_end.any()) {
    nlohmann::json counters;
    add_front_end(counters, render.front_end);
    j["stages"][std::string(stage_name(StageId::FrontEnd))].update(counters);
  }
  return j;
}

}  // namespace rastsim::sc
