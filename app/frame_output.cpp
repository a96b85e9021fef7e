// SPDX-License-Identifier: Apache-2.0
#include "frame_output.h"

#include <stdexcept>

#include "fidelity/frame_sampled.h"
#include "image/image_io.h"

namespace rastsim::app {

void add_frames_option(CLI::App* cmd, std::string& frames) {
  cmd->add_option("--frames", frames,
                  "Run frames A..B-1 of a multi-frame trace (`frame` ends a frame; numbered from 0, B excluded; "
                  "'A:' to the last, 'A' one frame): the frames before A are replayed by the reference model "
                  "(untimed: raster state, framebuffer colour and depth carried; simulate's pipeline and caches start "
                  "empty), "
                  "stats frames[] lists the range (docs/trace-format.md, Frames)")
      ->type_name("A:B");
}

FrameOutput::FrameOutput(const std::string& frames_text, const std::string& image_path) : image(image_path) {
  if (!frames_text.empty()) range = fidelity::parse_frame_range(frames_text);
  pattern = !image.empty() && fidelity::is_frame_pattern(image);
  if (!image.empty()) check_image_path(pattern ? fidelity::frame_image_path(image, 0) : image);
}

void FrameOutput::on_frame(const fidelity::FrameCounts& c, const Framebuffer& unresolved) {
  ++frames_seen;
  if (!wanted(c.index)) return;
  frames.push_back(fidelity::frame_json(c));
  if (pattern)
    write_image(unresolved.samples > 1 ? unresolved.resolve() : unresolved, fidelity::frame_image_path(image, c.index));
}

void FrameOutput::check_done() const {
  if (range.given) fidelity::check_frame_range(range, frames_seen);
}

void FrameOutput::add_to(nlohmann::json& j) const {
  if (frames_seen <= 1 && !range.given) return;
  j["frames"] = frames;
  if (range.given) j["frames_range"] = {range.first, std::min(range.last, frames_seen)};
}

void replay_frames(const Scene& scene, const ArchParams& arch, FrameOutput& out, Framebuffer* before,
                   Framebuffer* last) {
  RenderStats stats;
  fidelity::FrameRenderer r(arch, stats, [&](const fidelity::FrameCounts& c, const Framebuffer& fb) {
    if (before && c.index + 1 == out.range.first) *before = fb;
    if (last && c.index + 1 == out.range.last) *last = fb.samples > 1 ? fb.resolve() : fb;
    out.on_frame(c, fb);
  });
  r.stop_at(out.range.last);
  r.feed(scene.commands);
  r.finish();
  out.check_done();
}

CosimFrames::CosimFrames(const Scene& scene, const ArchParams& arch, const std::string& frames_text)
    : out(frames_text, ""),
      before(arch.raster.fb_width, arch.raster.fb_height, arch.raster.samples),
      reference(arch.raster.fb_width, arch.raster.fb_height) {
  const std::vector<fidelity::FrameSpan> spans = fidelity::frame_spans(scene.commands);
  out.range = fidelity::check_frame_range(out.range, spans.size());
  replay_frames(scene, arch, out, &before, &reference);
  slice = fidelity::slice_frames(scene, spans, out.range);
}

std::vector<uint64_t> slice_cycles(const fidelity::FrameSlice& slice, const std::vector<uint64_t>& starts,
                                   uint64_t end_cycle) {
  std::vector<fidelity::FrameSpan> timed = fidelity::frame_spans(slice.scene.commands);
  if (slice.prefix > 0) timed.erase(timed.begin());  // the carried viewport and scissor: not a frame
  return fidelity::span_cycles(timed, starts, end_cycle);
}

void CosimFrames::add_to(nlohmann::json& j, const std::vector<uint64_t>& rtl, const std::vector<uint64_t>& model,
                         const std::vector<uint64_t>& mismatches) {
  for (size_t k = 0; k < out.frames.size(); ++k) {
    nlohmann::json& f = out.frames[k];
    f["cycles_rtl"] = rtl.at(k);
    f["mismatches"] = mismatches.at(k);
    if (k < model.size()) {
      f["cycles_model"] = model[k];
      f["cycle_error"] = rtl[k] ? (double(model[k]) - double(rtl[k])) / double(rtl[k]) : 0.0;
    }
  }
  out.add_to(j);
}

}  // namespace rastsim::app
