// SPDX-License-Identifier: Apache-2.0
// Multi-frame scenes (the trace's `frame` command, docs/trace-format.md "Frames"): where
// each frame's commands lie, the reference model run frame by frame (a present's image
// and counters), the analytic walk's per-frame work, `--frames A:B` and `-o out_%04d.png`.
//
// A frame is the commands from one `frame` (or the start) to the next (or the end):
// Command::frame_line marks each frame's first command. An OBJ mesh is one frame.
// Between frames everything carries over, as one long command stream: the raster state
// (viewport, scissor; the texture state rides on each primitives command), the
// framebuffer's colour and depth (a present does not clear: a frame that wants a clean
// buffer clears it, as the generated sequences do), and the memory system's caches.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/arch_params.h"
#include "estimate/estimate.h"
#include "ref/framebuffer.h"
#include "ref/pipeline.h"
#include "ref/scene.h"
#include "timing/stage_table.h"

namespace rastsim::fidelity {

// Frame k: commands [begin, end) of the scene; `line` its first command's line.
struct FrameSpan {
  size_t begin = 0, end = 0;
  int line = 0;
};
std::vector<FrameSpan> frame_spans(const std::vector<Command>& commands);

// Where a frame's cycles are measured (frames[].cycles, frame sampling's y; the stats'
// frame_boundary). Frame k (> 0) starts, and frame k - 1 ends, at
// - Rop: the cycle the ROP takes frame k's first command, a state item there (a clear,
//   viewport, scissor or 2D command: they travel down the triangle path in program
//   order, after every fragment of the frames before): the end of frame k - 1's work at
//   the pipeline's last stage. Used when every frame after the first starts with such a
//   command and pipeline.mode is immediate (the generated and imported sequences: each
//   frame starts with its clear).
// - Fetch: the cycle command fetch starts frame k's first command (any other scene).
// Either way frame 0 starts at the run's start and the last frame ends at the run's end,
// so the frames' cycles sum to the run's. At the ROP a frame's cycles are where its work
// is done: on glmark2's texture scene (12 triangles a frame, each about 40,000 cycles of
// the texture stage) command fetch runs W triangles, 4 frames, ahead, so fetch to fetch
// a frame's cycles were its predecessor's drain with the FIFOs full, and the frames in
// the pipeline's fill took 48 cycles each (docs/results.md).
enum class FrameBoundary { Fetch, Rop };
FrameBoundary frame_boundary(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch);
const char* frame_boundary_name(FrameBoundary b);  // "fetch", "rop"

// `--frames A:B`: frames A..B-1, numbered from 0 (B excluded, as a Python slice); "A:" runs
// to the last frame, "A" alone is frame A. Throws std::runtime_error naming the text.
struct FrameRange {
  size_t first = 0, last = SIZE_MAX;  // [first, last)
  bool given = false;
};
FrameRange parse_frame_range(const std::string& text);
// The range clipped to `frames` frames; an error when it is empty or starts past the end.
FrameRange check_frame_range(FrameRange r, size_t frames);

// `-o` with one printf integer conversion (%d, %04d, %i, %u; `%%` a literal %): one image
// a frame, the conversion replaced by the frame number. A name without one, given more
// than one frame to write, is an error (frame_image_path).
bool is_frame_pattern(const std::string& path);
std::string frame_image_path(const std::string& pattern, size_t frame);

// One frame's counts from the reference model (functional, exact).
struct FrameCounts {
  size_t index = 0;
  int line = 0;
  uint64_t commands = 0, triangles_in = 0, triangles_rasterized = 0, tiles_visited = 0, pixel_tests = 0,
           fragments = 0, fragments_passed = 0, dram_bytes_read = 0, dram_bytes_written = 0;
  uint32_t crc32 = 0;  // the colour buffer at the frame's end (resolved when multisampled)
};

// The reference model fed a stream of commands (whole or in batches, in order), calling
// on_frame at each frame's end with its counts and the framebuffer (unresolved) as the
// present left it. finish() ends the last frame and the run (resolve, flush) and
// returns the final framebuffer (resolved, as render_scene's).
class FrameRenderer {
 public:
  using OnFrame = std::function<void(const FrameCounts&, const Framebuffer& unresolved)>;
  FrameRenderer(const ArchParams& arch, RenderStats& stats, OnFrame on_frame, int threads = 1,
                const FragmentSink& on_fragment = {});
  ~FrameRenderer();
  void feed(std::span<const Command> commands);
  Framebuffer finish();
  size_t frames_done() const { return index_; }
  // Frames from stop_at on are not drawn (--frames A:B stops after B - 1): feed ignores
  // their commands, and finish() ends no further frame.
  void stop_at(size_t frame) { stop_at_ = frame; }
  int threads() const;

 private:
  void end_frame(const Framebuffer* last);
  RenderStats& stats_;
  RenderStats at_start_;  // the counters when the current frame began
  OnFrame on_frame_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  size_t index_ = 0, stop_at_ = SIZE_MAX;
  uint64_t commands_ = 0;
  int line_ = 0;
};

// The analytic walk's work of each frame (model/estimate): per-stage busy cycles and
// the ROP's framebuffer bytes, differences of the walk's running totals at the frames'
// first commands (busy equal to the SystemC stages', docs/estimate.md).
struct FrameWork {
  std::array<uint64_t, kStageCount> busy{};
  uint64_t framebuffer_bytes = 0, triangles = 0, fragments = 0;
  // memory.model = "dram", after add_frame_dram_reads: the reference's DRAM bytes read in
  // the frame (frames[].dram_bytes_read) and those bytes over the DRAM's peak bytes a
  // core cycle (EstimateResult::dram_peak_bytes_per_cycle), cycles; 0 otherwise.
  uint64_t dram_bytes_read = 0;
  double dram_read_cycles = 0;
  uint64_t bottleneck() const;  // the busiest stage's busy cycles
  // Frame sampling's x, cycles: bottleneck() + dram_read_cycles. A line fill stalls the
  // ROP's transaction until its data arrives (timing/memory_timing.h) while writes are
  // posted, so reads add to the bottleneck's time rather than overlap it (docs/fidelity.md).
  double size() const { return double(bottleneck()) + dram_read_cycles; }
};
// `reference`: the reference's counts of the whole scene, if the caller has them
// (estimate_scene's; frame sampling's functional pass).
std::vector<FrameWork> frame_work(const Scene& scene, const ArchParams& arch, EstimateResult* whole = nullptr,
                                  const RenderStats* reference = nullptr);
// memory.model = "dram": each frame's dram_bytes_read and dram_read_cycles from the
// reference's bytes read frame by frame (`bytes`, one a frame: FrameRenderer's
// FrameCounts::dram_bytes_read, or frame sampling's functional pass), `peak` bytes a core
// cycle. Does nothing with memory.model = "fixed".
void add_frame_dram_reads(const ArchParams& arch, const std::vector<uint64_t>& bytes, double peak,
                          std::vector<FrameWork>& work);

// The commands of frames [r.first, r.last), preceded by the raster state the frames
// before them left (their last viewport and scissor, if any): `prefix` says how many
// leading commands are that carried state (timed, not measured).
// The raster state the commands before `upto` leave: their last viewport and scissor
// commands, if any, as commands of no frame (frame_line 0).
std::vector<Command> carried_state(const Scene& scene, size_t upto);
struct FrameSlice {
  Scene scene;
  size_t prefix = 0;
};
FrameSlice slice_frames(const Scene& scene, const std::vector<FrameSpan>& spans, FrameRange r);

// frames[] entries: the counts, plus (when given) the frame's cycles and per-stage busy.
nlohmann::json frame_json(const FrameCounts& c);
void add_frame_work(nlohmann::json& j, const FrameWork& w);

}  // namespace rastsim::fidelity
