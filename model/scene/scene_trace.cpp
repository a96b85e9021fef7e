// SPDX-License-Identifier: Apache-2.0
// Trace parser: the line-based scene format of docs/trace-format.md into a Scene.
//
// - Text handling (file reading, lines, tokens, numbers, errors) is in scene_text.h,
//   shared with the OBJ parser.
// - TraceParser: one method per command; a strip or fan is collected until its `end`
//   and emitted as one CmdPrimitives whose SourceLoc is its first vertex's line.
// - Coordinates go through Q64::parse_decimal so the scene holds the exact decimal
//   value (round to odd), never a double that setup would round a second time.
// - Clip-space input (`tri4`, `v4` in a block, `points`) is IEEE binary32, each number
//   rounded once from its decimal text (scene_text::parse_float), with the front-end
//   state (`texcoord`, `viewport_xform`, `depth_range`, `point_size`, `point_sprite`)
//   carried by each command as its ClipState (docs/clip-space.md).
// - Texture state (`texture`, `bindtexture`, `texfilter`, `texwrap`, `texenv`, `mipmap`,
//   `texlod_bias`) is carried by every primitives command as its TextureState
//   (docs/texture.md); a `texture` line decodes its file when it is read.
// - Every malformed input ends in a SceneError; nothing here indexes past a token list
//   or trusts a number's size before checking it.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <filesystem>
#include <optional>
#include <string_view>
#include <tuple>

#include "ref/2d/font.h"
#include "ref/framebuffer.h"
#include "ref/pipeline.h"
#include "ref/2d/rop3.h"
#include "ref/scene.h"
#include "scene/scene_text.h"
#include "scene/scene_io.h"
#include "scene/scene_stream.h"
#include "scene/texture_file.h"

namespace rastsim {



namespace {

using scene_text::quote;
using scene_text::Tokens;

// Largest viewport or scissor coordinate a trace may name: the largest framebuffer the
// config accepts.
constexpr int64_t kMaxExtent = kMaxImageExtent;

// "[-+]digits[.digits]" with at least one digit: the grammar Q64::parse_decimal reads.
bool is_plain_decimal(std::string_view tok) {
  if (!tok.empty() && (tok[0] == '-' || tok[0] == '+')) tok.remove_prefix(1);
  bool digit = false, dot = false;
  for (char c : tok) {
    if (c >= '0' && c <= '9') digit = true;
    else if (c == '.' && !dot) dot = true;
    else return false;
  }
  return digit;
}

class TraceParser {
 public:
  explicit TraceParser(const std::string& name) : name_(name) { scene_.source = name; }

  void line(int n, const Tokens& t) {
    line_ = n;
    using Handler = void (TraceParser::*)(const Tokens&);
    // `emits`: the command makes a command of its own, which would land before the
    // strip/fan it interrupts (that is emitted at `end`), so it may not appear inside one;
    // nor may the front-end state a block's command carries as a whole (viewport_xform,
    // depth_range, point_sprite), which a block takes as it stands at its `end`.
    struct Entry {
      std::string_view keyword;
      Handler handler;
      bool emits;
    };
    static constexpr Entry kCommands[] = {
        {"viewport", &TraceParser::viewport, true}, {"clear", &TraceParser::clear, true},
        {"cleardepth", &TraceParser::cleardepth, true}, {"scissor", &TraceParser::scissor, true},
        {"tri", &TraceParser::tri, true},           {"strip", &TraceParser::begin, true},
        {"fan", &TraceParser::begin, true},         {"color", &TraceParser::color, false},
        {"depth", &TraceParser::depth, false},      {"v", &TraceParser::vertex, false},
        {"end", &TraceParser::end, false},
        // 2D drawing (docs/2d.md) and its state.
        {"point", &TraceParser::point, true},       {"point_size", &TraceParser::point_size, false},
        {"line", &TraceParser::line2d, true},       {"lines", &TraceParser::begin, true},
        {"linestrip", &TraceParser::begin, true},   {"lineloop", &TraceParser::begin, true},
        {"polygon", &TraceParser::begin, true},     {"quads", &TraceParser::begin, true},
        {"quadstrip", &TraceParser::begin, true},   {"circle", &TraceParser::circle, true},
        {"arc", &TraceParser::arc, true},
        {"rect", &TraceParser::rect, true},         {"blit", &TraceParser::blit, true},
        {"bgcolor", &TraceParser::bgcolor, false},  {"pattern", &TraceParser::pattern, false},
        {"rop3", &TraceParser::rop3, false},        {"text", &TraceParser::text, true},
        {"font", &TraceParser::font, false},
        // Clip-space input (docs/clip-space.md) and the front-end state.
        {"tri4", &TraceParser::tri4, true},         {"v4", &TraceParser::vertex4, false},
        {"points", &TraceParser::begin, true},      {"texcoord", &TraceParser::texcoord, false},
        {"viewport_xform", &TraceParser::viewport_xform, true},
        {"depth_range", &TraceParser::depth_range, true},
        {"point_sprite", &TraceParser::point_sprite, true},
        // Texture state (docs/texture.md): what a block draws with is fixed at its start.
        {"texture", &TraceParser::texture, true},   {"bindtexture", &TraceParser::bindtexture, true},
        {"texfilter", &TraceParser::texfilter, true}, {"texwrap", &TraceParser::texwrap, true},
        {"texenv", &TraceParser::texenv, true},     {"mipmap", &TraceParser::mipmap, true},
        {"texlod_bias", &TraceParser::texlod_bias, true},
        // Present (docs/trace-format.md, "Frames"): the frame so far ends.
        {"frame", &TraceParser::frame, true}};
    for (const Entry& e : kCommands) {
      if (e.keyword != t[0]) continue;
      if (e.emits && open_)
        fail(quote(t[0]) + " inside the '" + open_kw_ + "' begun at line " + std::to_string(open_line_) +
             " (missing 'end'?)");
      return (this->*e.handler)(t);
    }
    fail("unknown command " + quote(t[0]));
  }

  Scene finish() {
    if (open_) {
      line_ = open_line_;
      fail("'" + open_kw_ + "' without 'end' (reached the end of the file)");
    }
    // A scene that draws nothing is a mistake (an empty or truncated file, the wrong
    // file), not a frame of clear colour to measure.
    if (!drew_)
      throw SceneError(name_ + ": no draw command (tri, strip, fan, quads or quadstrip, tri4 or points, or a 2D "
                               "draw: point, line, lines, linestrip, lineloop, polygon, circle, arc, rect, blit or "
                               "text)");
    return std::move(scene_);
  }

  // Hands the commands parsed so far to `consume` once there are at least `n` of them or
  // they took at least `n` lines (n = 0: whatever there is). Lines bound a batch of long
  // strips too (a 200-vertex strip is one command), so a reader thread hands the first
  // part of such a scene over after n lines, not after the whole file.
  void drain(size_t n, const CommandBatchFn& consume) {
    if (scene_.commands.empty()) return;
    if (scene_.commands.size() < n && static_cast<size_t>(line_ - drained_line_) < n) return;
    consume(scene_.commands);
    scene_.commands.clear();
    drained_line_ = line_;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { scene_text::fail(name_, line_, what); }

  void args(const Tokens& t, size_t n, const char* usage) const {
    if (t.size() - 1 != n)
      fail("'" + std::string(t[0]) + "' takes " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") +
           " (" + usage + "), got " + std::to_string(t.size() - 1));
  }

  int64_t integer(std::string_view tok, const std::string& what, int64_t lo, int64_t hi) const {
    const auto v = scene_text::parse_int(tok);
    if (!v) fail(what + " " + quote(tok) + " is not an integer");
    if (*v < lo || *v > hi)
      fail(what + " " + std::to_string(*v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return *v;
  }

  uint8_t channel(std::string_view tok, const std::string& what) const {
    return static_cast<uint8_t>(integer(tok, what, 0, 255));
  }

  // A depth in [0, 1]: plain decimal syntax (like coordinates), then the correctly
  // rounded double from from_chars.
  double unit(std::string_view tok, const std::string& what) const {
    const auto v = is_plain_decimal(tok) ? scene_text::parse_double(tok) : std::nullopt;
    if (!v) fail(what + " " + quote(tok) + " is not a decimal number");
    if (!(*v >= 0.0 && *v <= 1.0)) fail(what + " " + quote(tok) + " is outside [0, 1]");
    return *v;
  }

  // A coordinate, exact. Huge magnitudes are fine here (setup reports them against the
  // configured format); only the syntax is checked.
  Q64 coord(std::string_view tok, const std::string& what) const {
    if (!is_plain_decimal(tok)) fail(what + " " + quote(tok) + " is not a decimal number");
    try {
      return Q64::parse_decimal(tok);
    } catch (const std::invalid_argument& e) {
      // The syntax is fine, so this is a limit (e.g. fraction digits): keep its reason,
      // which parse_decimal gives after the quoted token.
      const std::string_view msg = e.what();
      const size_t at = msg.rfind("': ");
      fail(what + " " + quote(tok) + " is not an exact coordinate (" +
           std::string(at == std::string_view::npos ? msg : msg.substr(at + 3)) + ")");
    }
  }

  // The checks above for a vertex field, with the message's name built only on failure
  // (once a field of every vertex of a trace): "vertex K NAME" in a `tri` (k >= 0),
  // "NAME" on a `v` line (k < 0).
  static std::string field(int k, const char* name) {
    return k < 0 ? std::string(name) : "vertex " + std::to_string(k) + " " + name;
  }
  Q64 coord(std::string_view tok, int k, const char* name) const {
    if (is_plain_decimal(tok)) {
      try {
        return Q64::parse_decimal(tok);
      } catch (const std::invalid_argument&) {  // reported with its reason below
      }
    }
    return coord(tok, field(k, name));
  }
  double unit(std::string_view tok, int k, const char* name) const {
    if (is_plain_decimal(tok))
      if (const auto v = scene_text::parse_double(tok); v && *v >= 0.0 && *v <= 1.0) return *v;
    return unit(tok, field(k, name));
  }
  uint8_t channel(std::string_view tok, int k, const char* name) const {
    if (const auto v = scene_text::parse_int(tok); v && *v >= 0 && *v <= 255) return static_cast<uint8_t>(*v);
    return channel(tok, field(k, name));
  }

  // `x y` (current colour and depth) or `x y z r g b` starting at t[i]; k: see field().
  SceneVertex vertex_at(const Tokens& t, size_t i, bool full, int k) const {
    SceneVertex v;
    v.x = coord(t[i], k, "x");
    v.y = coord(t[i + 1], k, "y");
    v.s = s_, v.t = t_;
    if (!full) {
      v.z = depth_;
      v.r = r_, v.g = g_, v.b = b_;
      return v;
    }
    v.z = unit(t[i + 2], k, "z");
    v.r = channel(t[i + 3], k, "red");
    v.g = channel(t[i + 4], k, "green");
    v.b = channel(t[i + 5], k, "blue");
    return v;
  }

  // A clip-space number: IEEE binary32, rounded once from the decimal text.
  float clip_number(std::string_view tok, const std::string& what) const {
    const scene_text::ParsedFloat f = scene_text::parse_float(tok);
    switch (f.status) {
      case scene_text::FloatStatus::Ok: return f.value;
      case scene_text::FloatStatus::Malformed: fail(what + " " + quote(tok) + " is not a decimal number");
      case scene_text::FloatStatus::NotFinite:
        fail(what + " " + quote(tok) + " is not finite (a clip-space value is a finite binary32)");
      case scene_text::FloatStatus::Overflow:
        fail(what + " " + quote(tok) + " is outside the binary32 range (it rounds to infinity past 3.4028235e38)");
    }
    fail(what + " " + quote(tok) + " is not a number");
  }
  float clip_number(std::string_view tok, int k, const char* name) const {
    if (const auto f = scene_text::parse_float(tok); f.status == scene_text::FloatStatus::Ok) return f.value;
    return clip_number(tok, field(k, name));
  }

  // A clip-space vertex of `per` numbers starting at t[i] (docs/trace-format.md,
  // "Clip-space input"): x y z w (4; current colour and texcoord), then r g b (7), then
  // s t (9); k: see field().
  ClipVertex clip_vertex_at(const Tokens& t, size_t i, size_t per, int k) const {
    ClipVertex v;
    v.x = clip_number(t[i], k, "x");
    v.y = clip_number(t[i + 1], k, "y");
    v.z = clip_number(t[i + 2], k, "z");
    v.w = clip_number(t[i + 3], k, "w");
    v.r = r_, v.g = g_, v.b = b_;
    if (per >= 7) {
      v.r = channel(t[i + 4], k, "red");
      v.g = channel(t[i + 5], k, "green");
      v.b = channel(t[i + 6], k, "blue");
    }
    v.s = s_, v.t = t_;
    if (per == 9) {
      v.s = clip_number(t[i + 7], k, "s");
      v.t = clip_number(t[i + 8], k, "t");
    }
    return v;
  }

  // The front-end state a clip-space command carries: the `point_size` of 2D points
  // (the one point-size state) as the side of a 3D point's square.
  ClipState clip_state() const {
    ClipState c = clip_;
    c.point_size = float(style_.point_size);
    return c;
  }

  void emit(CommandBody body, int line) {
    drew_ = drew_ || std::holds_alternative<CmdPrimitives>(body) || std::holds_alternative<CmdDraw2d>(body);
    if (auto* p = std::get_if<CmdPrimitives>(&body)) p->texture = texture_;
    scene_.commands.push_back({std::move(body), SourceLoc{name_, line}, frame_line_});
    frame_line_ = 0;
    frame_has_command_ = true;
  }

  // `frame`: present. The next command emitted begins a new frame (Command::frame_line);
  // a `frame` at the end of the file ends the last frame and adds nothing. A frame with
  // no command is an error: a present of nothing is a truncated or misordered trace.
  void frame(const Tokens& t) {
    args(t, 0, "none: it ends the frame drawn so far");
    if (!frame_has_command_)
      fail(frame_line_ ? "'frame' right after the 'frame' at line " + std::to_string(frame_line_) +
                             ": a frame needs at least one command"
                       : std::string("'frame' before any command: the first frame needs at least one command"));
    frame_line_ = line_;
    frame_has_command_ = false;
  }

  void viewport(const Tokens& t) {
    args(t, 2, "W H");
    emit(CmdViewport{int(integer(t[1], "viewport width", 1, kMaxExtent)),
                     int(integer(t[2], "viewport height", 1, kMaxExtent))},
         line_);
  }

  void clear(const Tokens& t) {
    args(t, 3, "R G B, 0..255");
    emit(CmdClear{channel(t[1], "red"), channel(t[2], "green"), channel(t[3], "blue")}, line_);
  }

  void cleardepth(const Tokens& t) {
    args(t, 1, "Z in [0, 1]");
    emit(CmdClearDepth{unit(t[1], "clear depth")}, line_);
  }

  void scissor(const Tokens& t) {
    if (t.size() == 2 && t[1] == "off") return emit(CmdScissor{}, line_);
    args(t, 4, "X Y W H, or 'off'");
    CmdScissor s;
    s.enabled = true;
    s.x = int(integer(t[1], "scissor x", 0, kMaxExtent));
    s.y = int(integer(t[2], "scissor y", 0, kMaxExtent));
    s.width = int(integer(t[3], "scissor width", 0, kMaxExtent));
    s.height = int(integer(t[4], "scissor height", 0, kMaxExtent));
    emit(s, line_);
  }

  void color(const Tokens& t) {
    args(t, 3, "R G B, 0..255");
    r_ = channel(t[1], "red");
    g_ = channel(t[2], "green");
    b_ = channel(t[3], "blue");
    style_.color = {r_, g_, b_};
  }

  void depth(const Tokens& t) {
    args(t, 1, "Z in [0, 1]");
    depth_ = unit(t[1], "depth");
  }

  // One List command per `tri` line: its SourceLoc then names exactly that line.
  void tri(const Tokens& t) {
    const size_t n = t.size() - 1;
    if (n != 6 && n != 18)
      fail("'tri' takes 6 numbers (x y per vertex) or 18 (x y z r g b per vertex), got " + std::to_string(n));
    const bool full = n == 18;
    const size_t per = full ? 6 : 2;
    CmdPrimitives p;
    p.vertices.reserve(3);
    for (size_t k = 0; k < 3; ++k) p.vertices.push_back(vertex_at(t, 1 + k * per, full, int(k)));
    emit(std::move(p), line_);
  }

  // One clip-space List command per `tri4` line.
  void tri4(const Tokens& t) {
    const size_t n = t.size() - 1;
    if (n != 12 && n != 21 && n != 27)
      fail("'tri4' takes 12 numbers (x y z w per vertex), 21 (x y z w r g b per vertex) or 27 (x y z w r g b s t "
           "per vertex), got " + std::to_string(n));
    CmdPrimitives p;
    p.clip_vertices.reserve(3);
    for (size_t k = 0; k < 3; ++k) p.clip_vertices.push_back(clip_vertex_at(t, 1 + k * (n / 3), n / 3, int(k)));
    p.clip = clip_state();
    emit(std::move(p), line_);
  }

  // texcoord s t: the current texture coordinate of every following vertex (binary32).
  void texcoord(const Tokens& t) {
    args(t, 2, "s t, binary32 repeats");
    s_ = clip_number(t[1], "texcoord s");
    t_ = clip_number(t[2], "texcoord t");
  }

  // viewport_xform X Y W H (pixels) or `default` (the whole current viewport).
  void viewport_xform(const Tokens& t) {
    if (t.size() == 2 && t[1] == "default") {
      clip_.xform = ViewportXform{};
      return;
    }
    args(t, 4, "X Y W H, integers, W and H 1..16384; or 'default'");
    clip_.xform = {false, int(pixel_int(t[1], "viewport_xform x")), int(pixel_int(t[2], "viewport_xform y")),
                   int(integer(t[3], "viewport_xform width", 1, kMaxExtent)),
                   int(integer(t[4], "viewport_xform height", 1, kMaxExtent))};
  }

  // depth_range N F: where z/w = 0 and 1 land in depth, binary32 in [0, 1] (N > F allowed).
  void depth_range(const Tokens& t) {
    args(t, 2, "N F, each in [0, 1]");
    const float n = clip_number(t[1], "depth_range near"), f = clip_number(t[2], "depth_range far");
    for (const auto& [v, tok, what] : {std::tuple{n, t[1], "near"}, std::tuple{f, t[2], "far"}})
      if (!(v >= 0.0f && v <= 1.0f)) fail(std::string("depth_range ") + what + " " + quote(tok) + " is outside [0, 1]");
    clip_.depth_near = n;
    clip_.depth_far = f;
  }

  void point_sprite(const Tokens& t) {
    args(t, 1, "'on' or 'off'");
    if (t[1] != "on" && t[1] != "off") fail("point_sprite " + quote(t[1]) + " is not 'on' or 'off'");
    clip_.point_sprite = t[1] == "on";
  }

  // ---- Texture state (docs/texture.md): carried by every primitives command ----
  // texture ID FILE: FILE (relative to the trace's directory) decoded now; ID 0..65535,
  // a later `texture` of the same ID replaces it for later binds.
  void texture(const Tokens& t) {
    args(t, 2, "ID FILE: an integer 0..65535 and a PNG, TGA or JPEG file");
    const int id = int(integer(t[1], "texture ID", 0, 65535));
    const std::filesystem::path file{std::string(t[2])};
    const std::string path =
        file.is_absolute() ? file.string() : (std::filesystem::path(name_).parent_path() / file).string();
    textures_[id] = load_texture_file(path, name_, line_);
  }

  void bindtexture(const Tokens& t) {
    args(t, 1, "ID of a loaded texture, or 'none'");
    if (t[1] == "none") {
      texture_.image = nullptr;
      return;
    }
    const int id = int(integer(t[1], "texture ID", 0, 65535));
    const auto it = textures_.find(id);
    if (it == textures_.end()) fail("texture ID " + std::to_string(id) + " is not loaded (no 'texture " +
                                    std::to_string(id) + " FILE' before)");
    texture_.image = it->second;
  }

  // One keyword of `names` (in the enumerators' order) as that enum.
  template <class E, size_t N>
  E keyword(std::string_view tok, const char* what, const std::array<const char*, N>& names) const {
    std::string allowed;
    for (size_t k = 0; k < N; ++k) {
      if (tok == names[k]) return static_cast<E>(k);
      allowed += std::string(k ? (k + 1 == N ? " or " : ", ") : "") + "'" + names[k] + "'";
    }
    fail(std::string(what) + " " + quote(tok) + " is not " + allowed);
  }
  static constexpr std::array<const char*, 3> kWrapNames{"repeat", "clamp", "mirror"};

  void texfilter(const Tokens& t) {
    args(t, 1, "nearest, bilinear or trilinear");
    texture_.filter = keyword<TexFilter>(t[1], "texfilter", std::array{"nearest", "bilinear", "trilinear"});
  }

  // texwrap MODE (both axes) or texwrap MODE_S MODE_T.
  void texwrap(const Tokens& t) {
    if (t.size() != 3) args(t, 1, "repeat, clamp or mirror; or one for s, then one for t");
    texture_.wrap_s = keyword<TexWrap>(t[1], "texwrap", kWrapNames);
    texture_.wrap_t = keyword<TexWrap>(t.back(), "texwrap", kWrapNames);
  }

  void texenv(const Tokens& t) {
    args(t, 1, "replace, modulate or decal");
    texture_.env = keyword<TexEnv>(t[1], "texenv", std::array{"replace", "modulate", "decal"});
  }

  void mipmap(const Tokens& t) {
    args(t, 1, "'on' or 'off'");
    texture_.mipmap = keyword<int>(t[1], "mipmap", std::array{"off", "on"}) == 1;
  }

  // texlod_bias B: levels in [-16, 16], rounded to the nearest 1/256 (ties away from 0).
  void texlod_bias(const Tokens& t) {
    args(t, 1, "B, levels in [-16, 16]");
    const auto v = is_plain_decimal(t[1]) ? scene_text::parse_double(t[1]) : std::nullopt;
    if (!v) fail("texlod_bias " + quote(t[1]) + " is not a decimal number");
    if (!(*v >= -double(kMaxLodBias) && *v <= double(kMaxLodBias))) fail("texlod_bias " + quote(t[1]) + " is outside [-16, 16]");
    texture_.lod_bias = int32_t(std::lround(*v * 256.0));
  }

  // Blocks of `v` lines closed by `end`: strip / fan (triangles), quads / quadstrip
  // (triangles too: split by the front end, winding kept), lines / linestrip /
  // lineloop and polygon (2D).
  void begin(const Tokens& t) {
    args(t, 0, "its vertices follow on 'v' lines up to 'end'");
    open_ = true;
    open_kw_ = std::string(t[0]);
    open_line_ = line_;
    first_vertex_line_ = 0;
    open_prims_ = CmdPrimitives{t[0] == "fan" ? Topology::Fan : t[0] == "strip" ? Topology::Strip : Topology::List, {}};
  }

  bool open_is_2d() const { return open_kw_ == "lines" || open_kw_ == "linestrip" || open_kw_ == "lineloop" ||
                                   open_kw_ == "polygon"; }

  void vertex(const Tokens& t) {
    if (!open_) fail("'v' outside a strip or fan (or a quads, quadstrip, lines, linestrip, lineloop or polygon block)");
    if (open_kw_ == "points") fail("'v' in a 'points' block: 3D points take 'v4 x y z w' (4, 7 or 9 numbers)");
    if (!open_prims_.clip_vertices.empty()) mixed("v", "v4");
    const size_t n = t.size() - 1;
    if (open_is_2d()) {
      if (n != 2) fail("'v' in a '" + open_kw_ + "' takes 2 numbers (x y), got " + std::to_string(n));
    } else if (n != 2 && n != 6) {
      fail("'v' takes 2 numbers (x y) or 6 (x y z r g b), got " + std::to_string(n));
    }
    if (open_prims_.vertices.empty()) first_vertex_line_ = line_;
    open_prims_.vertices.push_back(vertex_at(t, 1, n == 6, -1));
  }

  [[noreturn]] void mixed(const char* kw, const char* others) const {
    fail(std::string("'") + kw + "' in the '" + open_kw_ + "' begun at line " + std::to_string(open_line_) +
         ", whose vertices are '" + others + "': a block's vertices are all 'v' or all 'v4'");
  }

  // v4 x y z w [r g b [s t]]: a clip-space vertex of the open block (not a polygon).
  void vertex4(const Tokens& t) {
    if (!open_)
      fail("'v4' outside a block (strip, fan, quads, quadstrip, lines, linestrip, lineloop or points)");
    if (open_kw_ == "polygon") fail("'v4' in a 'polygon': a polygon is 2D, its vertices are 'v x y'");
    if (!open_prims_.vertices.empty()) mixed("v4", "v");
    const size_t n = t.size() - 1;
    if (n != 4 && n != 7 && n != 9)
      fail("'v4' takes 4 numbers (x y z w), 7 (x y z w r g b) or 9 (x y z w r g b s t), got " + std::to_string(n));
    if (open_prims_.clip_vertices.empty()) first_vertex_line_ = line_;
    open_prims_.clip_vertices.push_back(clip_vertex_at(t, 1, n, -1));
  }

  // A block of `v4` vertices: a clip-space command with the front-end state at `end`.
  void end_clip() {
    CmdPrimitives& p = open_prims_;
    p.clip = clip_state();
    if (open_kw_ == "quads" || open_kw_ == "quadstrip") p.clip_vertices = split_quads(p.clip_vertices);
    if (open_kw_ == "points") p.topology = Topology::Points;
    if (open_kw_ == "lines") p.topology = Topology::Lines;
    if (open_kw_ == "linestrip") p.topology = Topology::LineStrip;
    if (open_kw_ == "lineloop") p.topology = Topology::LineLoop;
    emit(std::move(p), first_vertex_line_);
  }

  void end(const Tokens& t) {
    if (!open_) fail("'end' without a 'strip' or 'fan' (or a 'quads', 'quadstrip', 'lines', 'linestrip', "
                     "'lineloop', 'polygon' or 'points')");
    args(t, 0, "none");
    const size_t n = open_prims_.vertices.size() + open_prims_.clip_vertices.size();
    const int at = line_;
    line_ = open_line_;  // count errors name the block's line
    auto need = [&](bool ok, const std::string& what) {
      if (!ok) fail("'" + open_kw_ + "' has " + std::to_string(n) + " vertices; it needs " + what);
    };
    if (open_kw_ == "strip" || open_kw_ == "fan") need(n >= 3, "at least 3");
    if (open_kw_ == "quads") need(n >= 4 && n % 4 == 0, "a multiple of 4");
    if (open_kw_ == "quadstrip") need(n >= 4 && n % 2 == 0, "an even number, at least 4");
    if (open_kw_ == "lines") need(n >= 2 && n % 2 == 0, "an even number, at least 2");
    if (open_kw_ == "linestrip" || open_kw_ == "lineloop") need(n >= 2, "at least 2");
    if (open_kw_ == "polygon") need(n >= 3, "at least 3");
    if (open_kw_ == "points") need(n >= 1, "at least 1");
    line_ = at;
    open_ = false;
    if (open_prims_.clip_space()) return end_clip();
    if (open_is_2d()) {
      std::vector<Vertex2d> v;
      for (const SceneVertex& sv : open_prims_.vertices) v.push_back({sv.x, sv.y});
      line_ = open_line_;
      if (open_kw_ == "polygon") return draw2d(Draw2dPolygon{std::move(v)}, "polygon", true);
      const LineTopology top = open_kw_ == "lines" ? LineTopology::List
                               : open_kw_ == "linestrip" ? LineTopology::Strip : LineTopology::Loop;
      return draw2d(Draw2dLines{top, std::move(v)}, open_kw_ == "lines" ? "lines" : open_kw_ == "linestrip"
                                                                                   ? "linestrip" : "lineloop", false);
    }
    if (open_kw_ == "quads" || open_kw_ == "quadstrip") open_prims_.vertices = split_quads(open_prims_.vertices);
    emit(std::move(open_prims_), first_vertex_line_);
  }

  // Quads (a, b, c, d) -> triangles (a, b, c), (a, c, d); a quad strip's quad k is
  // (v2k, v2k+1, v2k+3, v2k+2). Both keep the quad's winding; the result is a list.
  template <class V>
  std::vector<V> split_quads(const std::vector<V>& v) const {
    std::vector<V> out;
    auto quad = [&](size_t a, size_t b, size_t c, size_t d) {
      for (size_t i : {a, b, c, a, c, d}) out.push_back(v[i]);
    };
    if (open_kw_ == "quads") {
      for (size_t k = 0; k + 3 < v.size(); k += 4) quad(k, k + 1, k + 2, k + 3);
    } else {
      for (size_t k = 0; k + 3 < v.size(); k += 2) quad(k, k + 1, k + 3, k + 2);
    }
    return out;
  }

  // ---- 2D drawing: every command takes the 2D state as it stands on its line ----
  void draw2d(Draw2dShape shape, const char* keyword, bool fill) {
    // No source operand outside a blit: a code whose result depends on S is meaningless.
    if (rop3_reads_source(style_.rop3))
      fail(std::string("'") + keyword + "' with rop3 " + hex2(style_.rop3) + ", which reads the source (S); only " +
           "'blit' has a source");
    Style2d st = style_;
    if (!fill) st.pattern_solid = true;  // lines, points and outlines draw the current colour
    emit(CmdDraw2d{std::move(shape), st, keyword}, line_);
  }

  static std::string hex2(uint8_t v) {
    const char* d = "0123456789ABCDEF";
    return std::string{d[v >> 4], d[v & 15]};
  }

  int64_t pixel_int(std::string_view tok, const std::string& what) const {
    return integer(tok, what, -kMaxExtent, kMaxExtent);
  }
  int64_t extent(std::string_view tok, const std::string& what) const { return integer(tok, what, 0, kMaxExtent); }

  void point(const Tokens& t) {
    args(t, 2, "x y");
    draw2d(Draw2dPoint{{coord(t[1], "x"), coord(t[2], "y")}}, "point", false);
  }

  void point_size(const Tokens& t) {
    args(t, 1, "S, pixels 1..256");
    style_.point_size = int(integer(t[1], "point size", 1, 256));
  }

  void line2d(const Tokens& t) {
    args(t, 4, "x0 y0 x1 y1");
    draw2d(Draw2dLines{LineTopology::Single,
                       {{coord(t[1], "x0"), coord(t[2], "y0")}, {coord(t[3], "x1"), coord(t[4], "y1")}}},
           "line", false);
  }

  void circle(const Tokens& t) {
    const bool fill = t.size() == 5 && t[4] == "fill";
    if (!fill) args(t, 3, "cx cy r, integers, then optionally 'fill'");
    draw2d(Draw2dCircle{int(pixel_int(t[1], "centre x")), int(pixel_int(t[2], "centre y")),
                        int(extent(t[3], "radius")), fill},
           "circle", fill);
  }

  void arc(const Tokens& t) {
    args(t, 5, "cx cy r a0 a1: integer centre and radius, angles in degrees counter-clockwise from +x");
    const double a0 = coord(t[4], "start angle").to_double(), a1 = coord(t[5], "end angle").to_double();
    if (a1 < a0) fail("arc end angle " + std::string(t[5]) + " is below its start angle " + std::string(t[4]) +
                      " (the arc runs counter-clockwise from a0 to a1; write a1 + 360)");
    draw2d(Draw2dArc{int(pixel_int(t[1], "centre x")), int(pixel_int(t[2], "centre y")), int(extent(t[3], "radius")),
                     a0, a1},
           "arc", false);
  }

  void rect(const Tokens& t) {
    args(t, 4, "x y w h, integers");
    draw2d(Draw2dRect{int(pixel_int(t[1], "rect x")), int(pixel_int(t[2], "rect y")), int(extent(t[3], "rect width")),
                      int(extent(t[4], "rect height"))},
           "rect", true);
  }

  void blit(const Tokens& t) {
    args(t, 6, "sx sy dx dy w h, integers");
    emit(CmdDraw2d{Draw2dBlit{int(pixel_int(t[1], "blit sx")), int(pixel_int(t[2], "blit sy")),
                              int(pixel_int(t[3], "blit dx")), int(pixel_int(t[4], "blit dy")),
                              int(extent(t[5], "blit width")), int(extent(t[6], "blit height"))},
                   style_, "blit"},
         line_);
  }

  // text x y STRING: the string is the rest of the line (inner blanks kept, a '#' still
  // starts a comment), with the escapes \\ and \xHH for what a line cannot hold.
  void text(const Tokens& t) {
    if (t.size() < 4) fail("'text' takes x y STRING (integers, then the rest of the line), got " +
                           std::to_string(t.size() - 1) + " argument" + (t.size() == 2 ? "" : "s"));
    const std::string_view raw(t[3].data(), size_t(t.back().data() + t.back().size() - t[3].data()));
    draw2d(Draw2dText{int(pixel_int(t[1], "text x")), int(pixel_int(t[2], "text y")), unescape_text(raw), font_},
           "text", true);
  }

  std::string unescape_text(std::string_view raw) const {
    std::string out;
    auto bad = [&](size_t col, const std::string& what) {
      fail("text character " + std::to_string(col + 1) + " of " + quote(raw) + ": " + what);
    };
    for (size_t i = 0; i < raw.size(); ++i) {
      unsigned char c = static_cast<unsigned char>(raw[i]);
      if (c == '\\') {
        if (i + 1 < raw.size() && raw[i + 1] == '\\') {
          ++i;
        } else if (i + 3 < raw.size() && raw[i + 1] == 'x' && hex_digit(raw[i + 2]) >= 0 && hex_digit(raw[i + 3]) >= 0) {
          c = static_cast<unsigned char>(hex_digit(raw[i + 2]) << 4 | hex_digit(raw[i + 3]));
          i += 3;
        } else {
          bad(i, "a backslash starts \\\\ or \\xHH");
        }
      }
      if (c < kFontFirstChar || c > kFontLastChar)
        bad(i, "not printable ASCII (the font has 0x20..0x7E only)");
      out += static_cast<char>(c);
    }
    return out;
  }

  // font SCALE [bold] [underline] [fixed|proportional] [transparent|opaque]: the whole
  // text state at once; a flag not named is off (fixed, transparent).
  void font(const Tokens& t) {
    if (t.size() < 2) fail("'font' takes SCALE (1..16) and any of bold, underline, fixed|proportional, "
                           "transparent|opaque");
    TextStyle f;
    f.scale = int(integer(t[1], "font scale", 1, 16));
    for (size_t i = 2; i < t.size(); ++i) {
      if (t[i] == "bold") f.bold = true;
      else if (t[i] == "underline") f.underline = true;
      else if (t[i] == "proportional") f.proportional = true;
      else if (t[i] == "fixed") f.proportional = false;
      else if (t[i] == "opaque") f.opaque = true;
      else if (t[i] == "transparent") f.opaque = false;
      else fail("font attribute " + quote(t[i]) + " is not one of bold, underline, fixed, proportional, "
                "transparent, opaque");
    }
    font_ = f;
  }

  void bgcolor(const Tokens& t) {
    args(t, 3, "R G B, 0..255");
    style_.bgcolor = {channel(t[1], "red"), channel(t[2], "green"), channel(t[3], "blue")};
  }

  static int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  }

  void pattern(const Tokens& t) {
    args(t, 1, "16 hex digits (8 rows, row 0 first, most significant bit leftmost), or 'solid'");
    if (t[1] == "solid") {
      style_.pattern_solid = true;
      return;
    }
    if (t[1].size() != 16) fail("pattern " + quote(t[1]) + " is not 16 hex digits");
    for (size_t i = 0; i < 16; ++i)
      if (hex_digit(t[1][i]) < 0) fail("pattern " + quote(t[1]) + " has a non-hex digit");
    for (size_t r = 0; r < 8; ++r) style_.pattern[r] = uint8_t(hex_digit(t[1][2 * r]) << 4 | hex_digit(t[1][2 * r + 1]));
    style_.pattern_solid = false;
  }

  void rop3(const Tokens& t) {
    args(t, 1, "a code of 2 hex digits, e.g. F0 (PATCOPY)");
    if (t[1].size() != 2 || hex_digit(t[1][0]) < 0 || hex_digit(t[1][1]) < 0)
      fail("rop3 code " + quote(t[1]) + " is not 2 hex digits");
    style_.rop3 = uint8_t(hex_digit(t[1][0]) << 4 | hex_digit(t[1][1]));
  }

  const std::string& name_;
  Scene scene_;
  int line_ = 0;
  uint8_t r_ = 255, g_ = 255, b_ = 255;  // `color`: white until set
  double depth_ = 0.0;                   // `depth`: nearest until set
  float s_ = 0.0f, t_ = 0.0f;            // `texcoord`: (0, 0) until set
  ClipState clip_;  // viewport_xform (whole viewport), depth_range (0 1), point_sprite (off)
  bool open_ = false;                    // inside strip/fan ... end
  bool drew_ = false;                    // a draw command was emitted
  int frame_line_ = 0;              // the pending `frame` line: the next command begins a frame
  bool frame_has_command_ = false;  // a command was emitted since the last `frame` (or the start)
  std::string open_kw_;
  int open_line_ = 0, first_vertex_line_ = 0;
  int drained_line_ = 0;  // the line of the last drain (batches bounded by lines too)
  CmdPrimitives open_prims_;
  // 2D state: white, black background, solid pattern, PATCOPY, 1-pixel points.
  Style2d style_{{255, 255, 255}, {0, 0, 0}, {}, true, kRopPatCopy, 1};
  TextStyle font_;  // `font 1`: scale 1, regular, fixed spacing, transparent
  std::map<int, std::shared_ptr<const TextureImage>> textures_;  // `texture ID FILE`
  TextureState texture_;  // none bound; bilinear, repeat, modulate, mipmap off, bias 0
};

}  // namespace

// The parser follows the name without its compression suffix: a.obj.gz is an OBJ.
bool is_obj_path(const std::string& path) {
  std::string ext = std::filesystem::path(scene_stream::strip_compression_suffix(path)).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj";
}

Scene parse_trace(const std::string& text, const std::string& name) {
  TraceParser p(name);
  scene_text::for_each_line(text, name, [&](int line, const Tokens& t) { p.line(line, t); });
  return p.finish();
}

Scene load_trace(const std::string& path) { return parse_trace(scene_text::read_file(path), path); }

void stream_trace(const std::string& path, size_t batch, const CommandBatchFn& consume) {
  scene_stream::Reader in(path);
  TraceParser p(path);
  scene_text::for_each_line(in, path, [&](int line, const Tokens& t) {
    p.line(line, t);
    p.drain(batch, consume);
  });
  Scene rest = p.finish();  // an unclosed strip/fan is an error here
  if (!rest.commands.empty()) consume(rest.commands);
}

void stream_scene(const std::string& path, const ObjPlacement& placement, size_t batch,
                  const CommandBatchFn& consume) {
  if (!is_obj_path(path)) return stream_trace(path, batch, consume);
  // An OBJ is placed by the bounding sphere of all its vertices: read whole, then batched.
  Scene scene = load_obj(path, placement);
  std::vector<Command> part;
  for (size_t i = 0; i < scene.commands.size(); i += std::max<size_t>(batch, 1)) {
    part.assign(std::make_move_iterator(scene.commands.begin() + std::ptrdiff_t(i)),
                std::make_move_iterator(scene.commands.begin() +
                                        std::ptrdiff_t(std::min(scene.commands.size(), i + std::max<size_t>(batch, 1)))));
    consume(part);
  }
}

Scene load_scene(const std::string& path, const ObjPlacement& placement) {
  if (is_obj_path(path)) return load_obj(path, placement);
  return load_trace(path);
}

}  // namespace rastsim
