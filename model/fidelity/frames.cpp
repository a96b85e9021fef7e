// SPDX-License-Identifier: Apache-2.0
#include "fidelity/frames.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "ref/pipeline.h"
#include "report/stats_json.h"

namespace rastsim::fidelity {

std::vector<FrameSpan> frame_spans(const std::vector<Command>& commands) {
  std::vector<FrameSpan> spans;
  for (size_t i = 0; i < commands.size(); ++i) {
    if (spans.empty() || commands[i].frame_line > 0) {
      if (!spans.empty()) spans.back().end = i;
      spans.push_back({i, i, commands[i].loc.line});
    }
  }
  if (!spans.empty()) spans.back().end = commands.size();
  return spans;
}

FrameBoundary frame_boundary(const Scene& scene, const std::vector<FrameSpan>& spans, const ArchParams& arch) {
  if (arch.raster.bin.mode != PipelineMode::Immediate) return FrameBoundary::Fetch;
  for (size_t k = 1; k < spans.size(); ++k)
    if (std::holds_alternative<CmdPrimitives>(scene.commands[spans[k].begin].body)) return FrameBoundary::Fetch;
  return FrameBoundary::Rop;
}

const char* frame_boundary_name(FrameBoundary b) { return b == FrameBoundary::Rop ? "rop" : "fetch"; }

namespace {

// A frame number of --frames: decimal digits only.
size_t frame_number(const std::string& tok, const std::string& text) {
  if (tok.empty() || tok.size() > 9 || tok.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("--frames: '" + text + "' is not A:B, A: or A (frame numbers from 0, B excluded)");
  return std::stoul(tok);
}

}  // namespace

FrameRange parse_frame_range(const std::string& text) {
  FrameRange r;
  r.given = true;
  const size_t colon = text.find(':');
  r.first = frame_number(text.substr(0, colon), text);
  if (colon == std::string::npos) r.last = r.first + 1;
  else if (colon + 1 < text.size()) r.last = frame_number(text.substr(colon + 1), text);
  if (r.last <= r.first) throw std::runtime_error("--frames: '" + text + "' is empty (B must be greater than A)");
  return r;
}

FrameRange check_frame_range(FrameRange r, size_t frames) {
  if (r.first >= frames)
    throw std::runtime_error("--frames: frame " + std::to_string(r.first) + " does not exist: the scene has " +
                             std::to_string(frames) + " frame" + (frames == 1 ? "" : "s") + " (0.." +
                             std::to_string(frames - 1) + ")");
  r.last = std::min(r.last, frames);
  return r;
}

// The position and length of the one integer conversion of `p` (npos: none); throws on
// a second one or on any other conversion, so the name is never handed to printf blind.
static std::pair<size_t, size_t> find_conversion(const std::string& p) {
  std::pair<size_t, size_t> at{std::string::npos, 0};
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] != '%') continue;
    if (i + 1 < p.size() && p[i + 1] == '%') {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < p.size() && (p[j] == '0' || p[j] == '-')) ++j;
    while (j < p.size() && p[j] >= '0' && p[j] <= '9') ++j;
    if (j >= p.size() || (p[j] != 'd' && p[j] != 'i' && p[j] != 'u') || j - i > 5 || at.first != std::string::npos)
      throw std::runtime_error("-o '" + p + "': a frame pattern takes one integer conversion (%d, %04d, %u; %% for a "
                               "literal %)");
    at = {i, j + 1 - i};
    i = j;
  }
  return at;
}

bool is_frame_pattern(const std::string& path) { return find_conversion(path).first != std::string::npos; }

std::string frame_image_path(const std::string& pattern, size_t frame) {
  const auto [at, len] = find_conversion(pattern);
  std::string out;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (i == at) {
      char buf[32];
      std::string spec = pattern.substr(at, len);
      spec.back() = 'd';
      std::snprintf(buf, sizeof buf, spec.c_str(), int(frame));
      out += buf;
      i += len - 1;
    } else {
      out += pattern[i];
      if (pattern[i] == '%') ++i;  // %% -> %
    }
  }
  return out;
}

struct FrameRenderer::Impl {
  SceneRenderer r;
  Impl(const ArchParams& a, RenderStats& s, int threads, const FragmentSink& sink)
      : r(a.raster, s, sink, Framebuffer::kDefaultTileLog2, threads, a.memory) {}
};

FrameRenderer::FrameRenderer(const ArchParams& arch, RenderStats& stats, OnFrame on_frame, int threads,
                             const FragmentSink& on_fragment)
    : stats_(stats),
      on_frame_(std::move(on_frame)),
      impl_(std::make_unique<Impl>(arch, stats, threads, on_fragment)) {}

int FrameRenderer::threads() const { return impl_->r.threads(); }

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::feed(std::span<const Command> commands) {
  size_t i = 0;
  while (i < commands.size() && index_ < stop_at_) {
    size_t j = i;
    if (commands[j].frame_line > 0 && commands_ > 0) {
      end_frame(nullptr);
      if (index_ >= stop_at_) return;
    }
    if (commands_ == 0) line_ = commands[j].loc.line;
    ++j;
    while (j < commands.size() && commands[j].frame_line == 0) ++j;
    impl_->r.run(commands.subspan(i, j - i));
    commands_ += j - i;
    i = j;
  }
}

// The counts of the frame since at_start_; `last`: the run's final (resolved) framebuffer.
void FrameRenderer::end_frame(const Framebuffer* last) {
  const Framebuffer& fb = last ? *last : impl_->r.frame_so_far();
  const RenderStats& s = stats_;
  const RenderStats& a = at_start_;
  FrameCounts c;
  c.index = index_;
  c.line = line_;
  c.commands = commands_;
  c.triangles_in = s.triangles_in - a.triangles_in;
  c.triangles_rasterized = s.triangles_rasterized - a.triangles_rasterized;
  c.tiles_visited = s.traversal.tiles_visited - a.traversal.tiles_visited;
  c.pixel_tests = s.traversal.pixel_tests - a.traversal.pixel_tests;
  c.fragments = s.traversal.fragments - a.traversal.fragments;
  c.fragments_passed = s.fragments_passed - a.fragments_passed;
  const auto rd = [](const MemoryStats& m) { return m.rop_color.bytes_read + m.rop_depth.bytes_read; };
  const auto wr = [](const MemoryStats& m) { return m.rop_color.bytes_written + m.rop_depth.bytes_written; };
  c.dram_bytes_read = rd(s.memory) - rd(a.memory);
  c.dram_bytes_written = wr(s.memory) - wr(a.memory);
  c.crc32 = last ? s.framebuffer_crc32 : fb.samples > 1 ? fb.resolve().color_crc32() : fb.color_crc32();
  on_frame_(c, fb);
  at_start_ = stats_;
  ++index_;
  commands_ = 0;
}

Framebuffer FrameRenderer::finish() {
  Framebuffer fb = impl_->r.finish();
  if (commands_ > 0) end_frame(&fb);
  return fb;
}

uint64_t FrameWork::bottleneck() const { return *std::max_element(busy.begin(), busy.end()); }

void add_frame_dram_reads(const ArchParams& arch, const std::vector<uint64_t>& bytes, double peak,
                          std::vector<FrameWork>& work) {
  if (!arch.memory.enabled || !(peak > 0)) return;
  if (bytes.size() != work.size()) throw std::logic_error("add_frame_dram_reads: not one byte count a frame");
  for (size_t k = 0; k < work.size(); ++k) {
    work[k].dram_bytes_read = bytes[k];
    work[k].dram_read_cycles = double(bytes[k]) / peak;
  }
}

std::vector<FrameWork> frame_work(const Scene& scene, const ArchParams& arch, EstimateResult* whole,
                                  const RenderStats* reference) {
  const std::vector<FrameSpan> spans = frame_spans(scene.commands);
  std::vector<FrameWork> at(spans.size() + 1);  // running totals at each frame's start, then the end
  const auto take = [](FrameWork& w, const EstimateResult& e) {
    for (size_t s = 0; s < kStageCount; ++s) w.busy[s] = e.stages[s].busy;
    w.framebuffer_bytes = e.framebuffer_bytes;
    w.triangles = e.render.triangles_in;
    w.fragments = e.render.traversal.fragments;
  };
  size_t next = 0;
  const EstimateResult e = estimate_scene(scene, arch, [&](size_t cmd, size_t tri, const EstimateResult& so_far) {
    if (tri == 0 && next < spans.size() && cmd == spans[next].begin) take(at[next++], so_far);
  }, reference);
  take(at[spans.size()], e);
  if (whole) *whole = e;
  std::vector<FrameWork> out(spans.size());
  for (size_t k = 0; k < spans.size(); ++k) {
    for (size_t s = 0; s < kStageCount; ++s) out[k].busy[s] = at[k + 1].busy[s] - at[k].busy[s];
    out[k].framebuffer_bytes = at[k + 1].framebuffer_bytes - at[k].framebuffer_bytes;
    out[k].triangles = at[k + 1].triangles - at[k].triangles;
    out[k].fragments = at[k + 1].fragments - at[k].fragments;
  }
  return out;
}

std::vector<Command> carried_state(const Scene& scene, size_t upto) {
  const Command *viewport = nullptr, *scissor = nullptr;
  for (size_t i = 0; i < upto; ++i) {
    const CommandBody& b = scene.commands[i].body;
    if (std::holds_alternative<CmdViewport>(b)) viewport = &scene.commands[i];
    if (std::holds_alternative<CmdScissor>(b)) scissor = &scene.commands[i];
  }
  std::vector<Command> out;
  for (const Command* c : {viewport, scissor})
    if (c) {
      out.push_back(*c);
      out.back().frame_line = 0;
    }
  return out;
}

FrameSlice slice_frames(const Scene& scene, const std::vector<FrameSpan>& spans, FrameRange r) {
  FrameSlice out;
  out.scene.source = scene.source;
  out.scene.commands = carried_state(scene, spans[r.first].begin);
  out.prefix = out.scene.commands.size();
  out.scene.commands.insert(out.scene.commands.end(), scene.commands.begin() + std::ptrdiff_t(spans[r.first].begin),
                            scene.commands.begin() + std::ptrdiff_t(spans[r.last - 1].end));
  return out;
}

nlohmann::json frame_json(const FrameCounts& c) {
  return {{"frame", c.index},
          {"line", c.line},
          {"commands", c.commands},
          {"triangles_in", c.triangles_in},
          {"triangles_rasterized", c.triangles_rasterized},
          {"tiles_visited", c.tiles_visited},
          {"pixel_tests", c.pixel_tests},
          {"fragments", c.fragments},
          {"fragments_passed", c.fragments_passed},
          {"dram_bytes_read", c.dram_bytes_read},
          {"dram_bytes_written", c.dram_bytes_written},
          {"framebuffer_crc32", crc32_hex(c.crc32)}};
}

void add_frame_work(nlohmann::json& j, const FrameWork& w) {
  j["framebuffer_bytes"] = w.framebuffer_bytes;
  for (const StageInfo& s : kStages) j["stages"][s.name]["busy"] = w.busy[stage_index(s.id)];
}

}  // namespace rastsim::fidelity
