// SPDX-License-Identifier: Apache-2.0
// The raster engine's stages and the links between them, declared once.
//
// Every list of stages or FIFOs in the project derives from these two tables: the
// SystemC pipeline's modules, their stall-RNG seeds and stats order (model/sc), the
// fill latencies (TimingParams::stage_fill_cycles), the analytic estimate's per-stage
// totals (model/estimate), the sampled level's FIFO capacity (model/fidelity), the RTL
// testbench's stage meters (model/rtlsim) and `rastsim config --stages`, which scripts read.
//
// Adding a stage is one StageId enumerator, one kStages row (with the next free stall
// stream) and its module; every `switch` over StageId or FifoId is written without a
// default, so a consumer that does not handle the new entry stops the build (-Wswitch
// under -Werror) instead of counting a wrong number.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace rastsim {

// The stages in pipeline order: the triangle path from command fetch to the ROP (with
// the geometry front end, which clip-space commands pass through between command fetch
// and primitive assembly and screen-space ones bypass), then the 2D path. The value is
// the stage index: its position in stats, timelines and reports.
enum class StageId : int {
  CommandFetch,
  FrontEnd,
  PrimAssembly,
  TriSetup,
  CoarseRaster,
  FineRaster,
  Interpolate,
  Texture,
  Rop,
  Draw2dSetup,
  Engine2d,
};

// What a transaction spends passing a stage before the next stage can start on it,
// beyond nothing: the term of TimingParams::stage_pass_cycles it adds to the fill of the
// stages downstream.
enum class StagePass {
  FetchHeader,        // command fetch: one command header (fetch.cycles_per_command)
  IssueCycle,         // one issue cycle (every cost is >= 1 cycle: schema minimums)
  IssueSetupLatency,  // one issue cycle plus setup's pipeline (latency - interval)
  IssueInterpLatency, // one issue cycle plus interpolation's pipeline latency
  IssueFrontEndLatency, // one issue cycle plus the geometry front end's pipeline latency
};

// Triangle: every triangle command; ClipSpace: the geometry front end, beside the
// triangle path from command fetch to primitive assembly, which only clip-space
// commands take (screen-space ones bypass it); Texture: the texture stage, beside the
// triangle path from interpolation to the ROP, which only textured batches take
// (untextured ones bypass it); TwoD: the 2D commands' path.
enum class StagePath { Triangle, ClipSpace, Texture, TwoD };
constexpr std::string_view stage_path_name(StagePath p) {
  switch (p) {
    case StagePath::Triangle: return "triangle";
    case StagePath::ClipSpace: return "clip_space";
    case StagePath::Texture: return "texture";
    case StagePath::TwoD: return "2d";
  }
  return "";
}

struct StageInfo {
  StageId id;
  std::string_view name;  // SystemC module, stats key, timeline lane, docs stem
  StagePath path;
  // The stage whose output this stage's first transaction waits for (fill order); the
  // first stage names itself. The 2D stages start behind command fetch's first header.
  StageId fed_by;
  StagePass pass;  // what passing this stage adds to the fill of the stages it feeds
  bool tile_heat;  // its busy cycles are attributed to screen tiles (simulate --heatmap)
  // The seed offset of its random stalls (sc/stage.h): fixed per stage, not its index,
  // so that a stage added to the table changes no other stage's stalls; a new stage
  // takes the next free number.
  int stall_stream;
};

inline constexpr std::array kStages = {
    StageInfo{StageId::CommandFetch, "command_fetch", StagePath::Triangle, StageId::CommandFetch, StagePass::FetchHeader, false, 0},
    StageInfo{StageId::FrontEnd, "front_end", StagePath::ClipSpace, StageId::CommandFetch, StagePass::IssueFrontEndLatency, false, 9},
    StageInfo{StageId::PrimAssembly, "prim_assembly", StagePath::Triangle, StageId::CommandFetch, StagePass::IssueCycle, false, 1},
    StageInfo{StageId::TriSetup, "tri_setup", StagePath::Triangle, StageId::PrimAssembly, StagePass::IssueSetupLatency, false, 2},
    StageInfo{StageId::CoarseRaster, "coarse_raster", StagePath::Triangle, StageId::TriSetup, StagePass::IssueCycle, true, 3},
    StageInfo{StageId::FineRaster, "fine_raster", StagePath::Triangle, StageId::CoarseRaster, StagePass::IssueCycle, true, 4},
    StageInfo{StageId::Interpolate, "interpolate", StagePath::Triangle, StageId::FineRaster, StagePass::IssueInterpLatency, true, 5},
    // Beside the path: only textured batches pass it (untextured fragments go from
    // interpolation to the ROP directly), so the ROP's fill stays interpolation's.
    StageInfo{StageId::Texture, "texture", StagePath::Texture, StageId::Interpolate, StagePass::IssueCycle, false, 10},
    StageInfo{StageId::Rop, "rop", StagePath::Triangle, StageId::Interpolate, StagePass::IssueCycle, true, 6},
    // Lower bound: a 2D command's first operation leaves command fetch with its header.
    StageInfo{StageId::Draw2dSetup, "draw2d_setup", StagePath::TwoD, StageId::CommandFetch, StagePass::IssueCycle, false, 7},
    StageInfo{StageId::Engine2d, "engine2d", StagePath::TwoD, StageId::CommandFetch, StagePass::IssueCycle, false, 8},
};
inline constexpr size_t kStageCount = kStages.size();

constexpr size_t stage_index(StageId id) { return size_t(id); }
constexpr const StageInfo& stage_info(StageId id) { return kStages[stage_index(id)]; }
constexpr std::string_view stage_name(StageId id) { return stage_info(id).name; }
// The last stage of the triangle path (its end: the ROP).
constexpr StageId last_triangle_stage() {
  StageId last = kStages[0].id;
  for (const StageInfo& s : kStages)
    if (s.path == StagePath::Triangle) last = s.id;
  return last;
}

// The links between stages: bounded FIFOs and the ROP's framebuffer port handshakes.
enum class FifoId : int {
  Command,   // command fetch -> primitive assembly: commands
  ClipCommand,  // command fetch -> geometry front end: clip-space commands
  Screen,    // geometry front end -> primitive assembly: screen-space triangles
  Triangle,  // primitive assembly -> setup: assembled triangles
  Setup,     // setup -> coarse raster: set-up triangles (plus setup's pipeline slots)
  Tile,      // coarse raster -> fine raster: tiles (or scanline spans)
  Pixel,     // fine raster -> interpolation: covered pixels
  Fragment,  // interpolation -> ROP: fragments (plus interpolation's pipeline slots); the
             // texture stage writes its textured batches here too, in order
  Texture,   // interpolation -> texture stage: textured batches (plus interpolation's pipeline slots)
  TextureDone,  // texture stage -> interpolation: a fence passed (one entry; the merge's order)
  Draw2d,    // command fetch -> 2D front end: 2D commands
  Op2d,      // 2D front end -> 2D engine: engine operations
  Grant2d,   // ROP -> 2D engine: the framebuffer port lent (one entry)
  Done2d,    // 2D engine -> ROP: the port handed back (one entry)
};

enum class LinkKind { Fifo, PortHandshake };

struct FifoInfo {
  FifoId id;
  std::string_view name;  // SystemC channel, stats key, timeline lane
  LinkKind kind;
  StageId writer, reader;
};

inline constexpr std::array kFifos = {
    FifoInfo{FifoId::Command, "command_fifo", LinkKind::Fifo, StageId::CommandFetch, StageId::PrimAssembly},
    FifoInfo{FifoId::ClipCommand, "clip_command_fifo", LinkKind::Fifo, StageId::CommandFetch, StageId::FrontEnd},
    FifoInfo{FifoId::Screen, "screen_fifo", LinkKind::Fifo, StageId::FrontEnd, StageId::PrimAssembly},
    FifoInfo{FifoId::Triangle, "triangle_fifo", LinkKind::Fifo, StageId::PrimAssembly, StageId::TriSetup},
    FifoInfo{FifoId::Setup, "setup_fifo", LinkKind::Fifo, StageId::TriSetup, StageId::CoarseRaster},
    FifoInfo{FifoId::Tile, "tile_fifo", LinkKind::Fifo, StageId::CoarseRaster, StageId::FineRaster},
    FifoInfo{FifoId::Pixel, "pixel_fifo", LinkKind::Fifo, StageId::FineRaster, StageId::Interpolate},
    FifoInfo{FifoId::Fragment, "fragment_fifo", LinkKind::Fifo, StageId::Interpolate, StageId::Rop},
    FifoInfo{FifoId::Texture, "texture_fifo", LinkKind::Fifo, StageId::Interpolate, StageId::Texture},
    FifoInfo{FifoId::TextureDone, "texture_done", LinkKind::PortHandshake, StageId::Texture, StageId::Interpolate},
    FifoInfo{FifoId::Draw2d, "draw2d_fifo", LinkKind::Fifo, StageId::CommandFetch, StageId::Draw2dSetup},
    FifoInfo{FifoId::Op2d, "op2d_fifo", LinkKind::Fifo, StageId::Draw2dSetup, StageId::Engine2d},
    FifoInfo{FifoId::Grant2d, "grant_2d", LinkKind::PortHandshake, StageId::Rop, StageId::Engine2d},
    FifoInfo{FifoId::Done2d, "done_2d", LinkKind::PortHandshake, StageId::Engine2d, StageId::Rop},
};
inline constexpr size_t kFifoCount = kFifos.size();

constexpr size_t fifo_index(FifoId id) { return size_t(id); }
constexpr const FifoInfo& fifo_info(FifoId id) { return kFifos[fifo_index(id)]; }
constexpr std::string_view fifo_name(FifoId id) { return fifo_info(id).name; }
// A FIFO between two stages of the triangle path.
constexpr bool on_triangle_path(const FifoInfo& f) {
  return f.kind == LinkKind::Fifo && stage_info(f.writer).path == StagePath::Triangle &&
         stage_info(f.reader).path == StagePath::Triangle;
}

// The tables are indexed by their enumerators; a row out of place is a build error.
constexpr bool tables_in_order() {
  for (size_t k = 0; k < kStageCount; ++k)
    if (stage_index(kStages[k].id) != k) return false;
  for (size_t k = 0; k < kFifoCount; ++k)
    if (fifo_index(kFifos[k].id) != k) return false;
  for (const StageInfo& s : kStages)  // fill order runs downstream only
    if (stage_index(s.fed_by) > stage_index(s.id)) return false;
  for (size_t a = 0; a < kStageCount; ++a)  // every stage its own stall stream
    for (size_t b = a + 1; b < kStageCount; ++b)
      if (kStages[a].stall_stream == kStages[b].stall_stream) return false;
  return true;
}
static_assert(tables_in_order(), "kStages / kFifos rows must follow their enumerators' order, stall streams distinct");

}  // namespace rastsim
