// SPDX-License-Identifier: Apache-2.0
#include "fidelity/functional_pass.h"

#include <algorithm>
#include <chrono>
#include <span>

namespace rastsim::fidelity {

WarmState::WarmState(const Framebuffer& f, const RopMemory* m, const ArchParams& arch) : fb(f) {
  if (!m) return;
  mem = std::make_unique<RopMemory>(arch.memory, fb, arch.raster.depth_bits);
  mem->take_state(*m);
}

size_t WarmState::bytes() const {
  // A tile: 2^(2 tile_log2) pixels x samples x 4 bytes (RGBA8 colour; 32-bit depth).
  const size_t tile = (size_t(1) << (2 * Framebuffer::kDefaultTileLog2)) * size_t(fb.samples) * 4;
  return (fb.color_tiles_allocated() + fb.depth_tiles_allocated()) * tile;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The ROP's DRAM bytes read so far (FrameRenderer's per-frame count: colour and depth).
uint64_t bytes_read(const RenderStats& s) { return s.memory.rop_color.bytes_read + s.memory.rop_depth.bytes_read; }

}  // namespace

FunctionalPass functional_pass(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch,
                               const std::vector<size_t>& starts, size_t budget) {
  const auto t0 = std::chrono::steady_clock::now();
  FunctionalPass out;
  SceneRenderer ref(arch.raster, out.stats, {}, Framebuffer::kDefaultTileLog2, 1, arch.memory);
  // Stops: every frame's first command (its predecessor's bytes end there) and every
  // snapshot start, ascending; the reference runs from one to the next.
  std::vector<size_t> stops(starts);
  for (const FrameSpan& s : spans) stops.push_back(s.begin);
  std::sort(stops.begin(), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
  std::vector<bool> snap(scene.commands.size() + 1, false);
  for (size_t i : starts) snap.at(i) = i > 0;
  size_t done = 0, frame = 0, used = 0;
  uint64_t last = 0;
  for (size_t at : stops) {
    ref.run(std::span<const Command>(scene.commands).subspan(done, at - done));
    done = at;
    const Framebuffer& fb = ref.frame_so_far();  // brings stats.memory up to here
    if (frame + 1 < spans.size() && at == spans[frame + 1].begin) {
      out.dram_bytes_read.push_back(bytes_read(out.stats) - last);
      last = bytes_read(out.stats);
      ++frame;
    }
    if (!snap[at] || used > budget) continue;
    auto w = std::make_unique<WarmState>(fb, ref.memory(), arch);
    used += w->bytes();
    if (used <= budget) out.warm.emplace(at, std::move(w));
  }
  ref.run(std::span<const Command>(scene.commands).subspan(done));
  ref.finish();  // the last frame's bytes include the frame end's (resolve reads)
  if (!spans.empty()) out.dram_bytes_read.push_back(bytes_read(out.stats) - last);
  out.seconds = seconds_since(t0);
  return out;
}

double warm_states_for(const Scene& scene, const ArchParams& arch, const std::vector<size_t>& starts,
                       WarmStates& have) {
  std::vector<size_t> need;
  for (size_t i : starts)
    if (i > 0 && !have.contains(i)) need.push_back(i);
  if (need.empty()) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::sort(need.begin(), need.end());
  RenderStats stats;
  SceneRenderer ref(arch.raster, stats, {}, Framebuffer::kDefaultTileLog2, 1, arch.memory);
  size_t done = 0;
  for (size_t at : need) {
    ref.run(std::span<const Command>(scene.commands).subspan(done, at - done));
    done = at;
    have.emplace(at, std::make_unique<WarmState>(ref.frame_so_far(), ref.memory(), arch));
  }
  return seconds_since(t0);
}

}  // namespace rastsim::fidelity
