// SPDX-License-Identifier: Apache-2.0
// Frame sampling's one functional pass (docs/fidelity.md, "Frame sampling", steps 1 and
// 4): the reference model over the whole scene once, frame by frame, giving
// - the whole scene's counts (render_scene's, finish() included), which the analytic
//   estimate's bounds take instead of a reference run of their own (estimate_scene's
//   `reference`),
// - each frame's DRAM bytes read (frames[].dram_bytes_read: the features' DRAM term),
// - the reference's state at each warm-up start asked for (the framebuffer and the ROP
//   memory clients' caches, dirty bits and fast-clear flags), which a segment's timed
//   run starts from (SimOptions::initial_fb, warm_memory).
// Before, these were three passes (the estimate's, the per-frame bytes', the warm-up's).
// The plan (which warm-ups are needed) depends on the per-frame bytes, so the pass keeps
// a snapshot at every frame's warm-up start while they fit in `budget` bytes; a segment
// whose start has none is warmed by a second pass (warm_states_for), as before. Either
// way the state is the same: the reference model run to the same command.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "config/arch_params.h"
#include "fidelity/frames.h"
#include "ref/framebuffer.h"
#include "ref/memory/rop_memory.h"
#include "ref/pipeline.h"
#include "ref/scene.h"

namespace rastsim::fidelity {

// The reference's state at one command: a timed run's starting point. Not movable: `mem`
// refers to `fb` (depth compression reads it at write-back).
struct WarmState {
  WarmState(const Framebuffer& f, const RopMemory* m, const ArchParams& arch);
  WarmState(const WarmState&) = delete;
  WarmState& operator=(const WarmState&) = delete;
  size_t bytes() const;  // the framebuffer's allocated tiles (the flags and caches: small beside them)
  Framebuffer fb;
  std::unique_ptr<RopMemory> mem;  // null with memory.model = "fixed"
};
using WarmStates = std::map<size_t, std::unique_ptr<WarmState>>;  // by command index

// The snapshots' default budget: 512 MiB (a 640x480 frame's colour and depth are 2.4 MB
// at most, so 100 frames' warm-up starts take 240 MB at most; a 1080p desktop frame
// drawn whole 16.6 MB).
inline constexpr size_t kWarmSnapshotBudget = size_t(512) << 20;

struct FunctionalPass {
  RenderStats stats;                      // the whole scene's, after finish()
  std::vector<uint64_t> dram_bytes_read;  // by frame, as FrameRenderer's FrameCounts
  WarmStates warm;                        // at the asked-for starts (those within the budget)
  double seconds = 0;                     // its wall time
};

// The pass over `scene` (its frames `spans`), snapshotting at each of `starts` (command
// indices; 0 needs none: a cold start) while the snapshots' bytes stay within `budget`.
FunctionalPass functional_pass(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch,
                               const std::vector<size_t>& starts, size_t budget = kWarmSnapshotBudget);

// The states at `starts` that `have` lacks (0 excluded), from a second reference pass up
// to the last of them (the fallback when the snapshots did not fit); added to `have`.
// Returns its wall time.
double warm_states_for(const Scene& scene, const ArchParams& arch, const std::vector<size_t>& starts,
                       WarmStates& have);

}  // namespace rastsim::fidelity
