// SPDX-License-Identifier: Apache-2.0
// Fuzz harness (fuzz/harness.h): the trace parser (model/scene/scene_trace.cpp, docs/trace-format.md).
//
// The input is a trace file's bytes. Plain text goes through parse_trace and, written to
// a scratch file, through stream_trace (the chunked reader `render` and `simulate` use):
// both must agree, command for command, or fail with the same message. Input that starts
// with gzip or zstd magic bytes is a compressed scene: it is written as fuzz.trace.gz /
// .zst and read by load_trace (whole) and stream_trace (chunked), which again must agree.
// Bad input may end only in SceneError; an accepted scene must respect the ranges
// docs/trace-format.md gives (checked below), and every decimal in the coordinate
// grammar must read as exactly the value strtod gives.
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>
#include <functional>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "fuzz_common.h"
#include "harness.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "scene/scene_stream.h"

namespace rastsim::fuzz {
namespace {

// Commands of a run as (line, kind) pairs: enough to tell two readings apart cheaply.
struct Outcome {
  bool ok = false;
  std::string error;
  std::vector<std::pair<int, size_t>> commands;
};

void check_vertex(const SceneVertex& v, int line) {
  const std::string at = "line " + std::to_string(line) + ": ";
  check(v.z >= 0.0 && v.z <= 1.0, at + "vertex depth outside [0, 1]");
  // Q64 holds up to 18 integer digits exactly (|v| < 1e18); beyond that it saturates.
  // A wrapped value would show as a finite double of the wrong size or sign.
  for (const Q64& q : {v.x, v.y})
    check(q.saturated() || std::abs(q.to_double()) <= 1e18, at + "coordinate wrapped");
}

// A clip-space command (tri4, v4 blocks): finite binary32 values, a vertex count its
// topology accepts, and front-end state within the ranges the trace format gives.
void check_clip(const CmdPrimitives& p, int line) {
  const std::string at = "line " + std::to_string(line) + ": ";
  check(p.vertices.empty(), at + "a clip-space command with screen-space vertices");
  const size_t n = p.clip_vertices.size();
  bool count_ok = n >= 1;
  switch (p.topology) {
    case Topology::List: count_ok = n % 3 == 0; break;
    case Topology::Strip:
    case Topology::Fan: count_ok = n >= 3; break;
    case Topology::Lines: count_ok = n % 2 == 0; break;
    case Topology::LineStrip:
    case Topology::LineLoop: count_ok = n >= 2; break;
    case Topology::Points: break;
  }
  check(count_ok, at + "vertex count of a clip-space primitive");
  for (const ClipVertex& v : p.clip_vertices)
    for (const float f : {v.x, v.y, v.z, v.w, v.s, v.t}) check(std::isfinite(f), at + "a clip-space value not finite");
  const ClipState& c = p.clip;
  check(c.depth_near >= 0 && c.depth_near <= 1 && c.depth_far >= 0 && c.depth_far <= 1, at + "depth range");
  check(c.point_size >= 1 && c.point_size <= 256, at + "3D point size");
  check(c.xform.whole_viewport || (c.xform.width >= 1 && c.xform.height >= 1), at + "viewport transform size");
}

void check_scene(const Scene& s, const std::string& name, size_t text_lines) {
  int prev = 0;
  for (const Command& c : s.commands) {
    const int line = c.loc.line;
    check(c.loc.file == name, "command names another file: " + c.loc.file);
    check(line >= 1 && size_t(line) <= text_lines + 1, "command line " + std::to_string(line) + " past the text");
    check(line >= prev, "commands out of line order");
    prev = line;
    const std::string at = "line " + std::to_string(line) + ": ";
    if (const auto* v = std::get_if<CmdViewport>(&c.body))
      check(v->width >= 1 && v->width <= 16384 && v->height >= 1 && v->height <= 16384, at + "viewport size");
    if (const auto* d = std::get_if<CmdClearDepth>(&c.body)) check(d->z >= 0.0 && d->z <= 1.0, at + "clear depth");
    if (const auto* sc = std::get_if<CmdScissor>(&c.body))
      check(sc->x >= 0 && sc->y >= 0 && sc->width >= 0 && sc->height >= 0 && sc->x <= 16384 && sc->y <= 16384 &&
                sc->width <= 16384 && sc->height <= 16384,
            at + "scissor rectangle");
    if (const auto* p = std::get_if<CmdPrimitives>(&c.body)) {
      if (p->clip_space()) {
        check_clip(*p, line);
      } else {
        const size_t n = p->vertices.size();
        check(p->topology == Topology::List ? n >= 3 && n % 3 == 0 : n >= 3, at + "vertex count of a primitive");
        for (const SceneVertex& v : p->vertices) check_vertex(v, line);
      }
    }
    if (const auto* d = std::get_if<CmdDraw2d>(&c.body)) {
      check(d->style.point_size >= 1 && d->style.point_size <= 256, at + "point size");
      if (const auto* t = std::get_if<Draw2dText>(&d->shape)) {
        check(t->style.scale >= 1 && t->style.scale <= 16, at + "font scale");
        for (char ch : t->str) check(ch >= 0x20 && ch <= 0x7e, at + "text character not printable ASCII");
      }
      if (const auto* a = std::get_if<Draw2dArc>(&d->shape)) check(a->a1 >= a->a0 && a->r >= 0, at + "arc");
      if (const auto* ci = std::get_if<Draw2dCircle>(&d->shape)) check(ci->r >= 0 && ci->r <= 16384, at + "radius");
      if (const auto* r = std::get_if<Draw2dRect>(&d->shape)) check(r->w >= 0 && r->h >= 0, at + "rect size");
    }
  }
}

// Coordinates are read exactly (Q64::parse_decimal: 64 fraction bits, rounded to odd),
// so converting one to double must give what the C library's strtod gives for the same
// text (one correct rounding), for every token of the input in the coordinate grammar;
// below 2^-9 the 64 fraction bits hold fewer than the 55 significant bits this needs.
void check_decimals(std::string_view text) {
  for_each_token(text, " \t\r\v\f\n", [](const std::string& tok) {
    std::string_view digits = tok;
    if (!digits.empty() && (digits[0] == '-' || digits[0] == '+')) digits.remove_prefix(1);
    const size_t dot = digits.find('.');
    const std::string_view ip = digits.substr(0, dot), fp = dot == std::string_view::npos ? "" : digits.substr(dot + 1);
    auto all_digits = [](std::string_view s) { return s.find_first_not_of("0123456789") == std::string_view::npos; };
    if ((ip.empty() && fp.empty()) || !all_digits(ip) || !all_digits(fp) || ip.size() > 18 || fp.size() > 36) return;
    Q64 q;
    try {
      q = Q64::parse_decimal(tok);
    } catch (const std::invalid_argument& e) {
      finding("parse_decimal rejects '" + tok + "', which is within its documented limits: " + e.what());
    }
    const double want = std::strtod(tok.c_str(), nullptr);
    if (want == 0.0 || std::abs(want) >= 1.0 / 512)
      check(q.to_double() == want, "'" + tok + "' reads as " + std::to_string(q.to_double()) + ", strtod gives " +
                                       std::to_string(want));
  });
}

void record(Outcome& o, const std::vector<Command>& cmds) {
  for (const Command& c : cmds) o.commands.emplace_back(c.loc.line, c.body.index());
}

Outcome run_whole(const std::function<Scene()>& parse, const std::string& name, size_t lines) {
  Outcome o;
  expect_only<SceneError>("SceneError", [&] {
    try {
      const Scene s = parse();
      check_scene(s, name, lines);
      record(o, s.commands);
      o.ok = true;
    } catch (const SceneError& e) {
      o.error = e.what();
      throw;
    }
  });
  return o;
}

Outcome run_stream(const std::string& path) {
  Outcome o;
  expect_only<SceneError>("SceneError", [&] {
    try {
      // Batches of 7: small enough that every trace of a few lines is split.
      stream_trace(path, 7, [&](std::vector<Command>& b) { record(o, b); });
      o.ok = true;
    } catch (const SceneError& e) {
      o.error = e.what();
      throw;
    }
  });
  return o;
}

// `same_error`: both readings must fail with the same message. Not for compressed
// input: the whole reading decompresses everything first (a truncated stream fails
// there), the streamed one parses each chunk as it comes (a bad line in the part before
// the truncation fails first); both are documented (scene_io.h).
void same(const Outcome& a, const Outcome& b, const char* what, bool same_error) {
  if (a.ok != b.ok) finding(std::string(what) + ": one reading accepts, the other fails: " + a.error + b.error);
  // A streamed reading hands out the commands before a bad line, then fails: compare
  // the messages only.
  if (!a.ok) {
    if (!same_error) return;
    check(a.error == b.error, std::string(what) + ": different errors: '" + a.error + "' vs '" + b.error + "'");
    return;
  }
  check(a.commands == b.commands, std::string(what) + ": different command streams");
}

}  // namespace

void trace_one(std::string_view input) {
  const std::string bytes(input);
  const scene_stream::Format f = scene_stream::sniff(bytes);
  size_t lines = 1;
  for (char c : bytes) lines += c == '\n';
  if (f == scene_stream::Format::Plain) {
    check_decimals(bytes);
    const std::string path = scratch_file("fuzz.trace", bytes);
    const Outcome whole = run_whole([&] { return parse_trace(bytes, path); }, path, lines);
    same(whole, run_stream(path), "parse_trace vs stream_trace", true);
  } else {
    const std::string path =
        scratch_file(f == scene_stream::Format::Gzip ? "fuzz.trace.gz" : "fuzz.trace.zst", bytes);
    // The decompressed text may have any number of lines: bound the check by a large one.
    const Outcome whole = run_whole([&] { return load_trace(path); }, path, size_t{1} << 40);
    same(whole, run_stream(path), "load_trace vs stream_trace (compressed)", false);
  }
}

}  // namespace rastsim::fuzz
