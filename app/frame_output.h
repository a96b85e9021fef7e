// SPDX-License-Identifier: Apache-2.0
// What render, simulate and estimate share for multi-frame scenes (docs/trace-format.md
// "Frames"): `--frames A:B`, `-o out_%04d.png` (one image a frame) and the stats' frames[].
#pragma once

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common.h"
#include "config/arch_params.h"
#include "fidelity/frames.h"
#include "sc/raster_pipeline.h"

namespace rastsim::app {

// --frames on a command (its --help text).
void add_frames_option(CLI::App* cmd, std::string& frames);

// The frames a run reports and the images it writes.
struct FrameOutput {
  fidelity::FrameRange range;    // --frames (all when not given)
  std::string image;             // -o: a pattern writes frames; a plain name only the last image
  bool pattern = false;
  nlohmann::json frames = nlohmann::json::array();  // frames[] of the frames in range
  size_t frames_seen = 0;        // frames ended so far (in range or not)

  FrameOutput(const std::string& frames_text, const std::string& image_path);
  bool wanted(size_t frame) const { return frame >= range.first && frame < range.last; }
  // A frame of the reference run ended: its entry, and its image under a pattern.
  void on_frame(const fidelity::FrameCounts& c, const Framebuffer& unresolved);
  // frames[] (and frames_range) into the stats when the scene has more than one frame or
  // --frames was given; an error when --frames asked for frames the scene lacks.
  void add_to(nlohmann::json& j) const;
  // After the run: a pattern that wrote nothing, or a range past the scene, is an error.
  void check_done() const;
};

// The reference model over `scene`'s frames [0, out.range.last) (functional): out gets
// the frames in range; `before`, if given, receives the framebuffer (unresolved) the
// frames before out.range.first left, the state a timed run of the range starts from;
// `last`, if given, the image (resolved) the range's last frame ends with.
void replay_frames(const Scene& scene, const ArchParams& arch, FrameOutput& out, Framebuffer* before = nullptr,
                   Framebuffer* last = nullptr);

// Each frame of a range's cycles in a timed run of its slice, from the run's per-command
// fetch starts (fidelity::record_command_starts; the carried state commands before the
// range excluded), the last to `end_cycle`.
std::vector<uint64_t> slice_cycles(const fidelity::FrameSlice& slice, const std::vector<uint64_t>& starts,
                                   uint64_t end_cycle);

// `rastsim cosim` on a multi-frame scene or with --frames A:B (app/cmd_cosim.cpp): the
// range's commands (the frames before it replayed by the reference model, functional),
// the framebuffer they leave (the RTL's and the SystemC model's start), the reference
// image after the range's last frame (the RTL's must equal it), frames[].
struct CosimFrames {
  FrameOutput out;
  fidelity::FrameSlice slice;
  Framebuffer before{1, 1}, reference{1, 1};
  CosimFrames(const Scene& scene, const ArchParams& arch, const std::string& frames_text);
  // frames[].{cycles_rtl, cycles_model, cycle_error, mismatches} and frames_range into j.
  void add_to(nlohmann::json& j, const std::vector<uint64_t>& rtl, const std::vector<uint64_t>& model,
              const std::vector<uint64_t>& mismatches);
};

// `rastsim simulate`'s multi-frame parts (app/simulate_frames.cpp). What a full run
// records of its frames: the cycle each frame after the first starts, at command fetch
// (`cycles`: fetch starting its first command) and at the ROP (`rop`: the ROP taking it,
// when it is a state item; fidelity::FrameBoundary says which frames[].cycles use) and,
// with memory.model = "dram", the DRAM's backlog at the fetch (MemorySystem::
// backlog_cycles, cycles).
struct FrameStarts {
  std::vector<uint64_t> cycles, rop, backlog;
  const MemorySystem* memory = nullptr;  // the run's (SimOptions::on_memory_system)
};
// Sets sim's on_fetch, on_rop_state and on_memory_system to fill `f`, which must outlive
// the run.
void record_frame_starts(sc::SimOptions& sim, FrameStarts& f);
// frames[] of a full run from those starts (nothing for one frame): the reference
// model's counts, the cycles, the DRAM backlog at the frame's start, the analytic walk's
// per-stage busy.
void add_frames_of_run(nlohmann::json& j, const SimulateOptions& o, const ArchParams& arch, const FrameStarts& f,
                       uint64_t end_cycle);
// --frames A:B or an -o pattern: the whole scene loaded, the range timed.
void run_simulate_frames(const SimulateOptions& o, const ArchParams& arch);
// --frame-sample F: the frame-sampled level.
void run_simulate_frame_sample(const SimulateOptions& o, const ArchParams& arch);

}  // namespace rastsim::app
