// SPDX-License-Identifier: Apache-2.0
// Trace parser: the line-based scene format of docs/trace-format.md into a Scene.
//
// - Text handling (file reading, lines, tokens, numbers, errors) is in scene_text.h,
//   shared with the OBJ parser.
// - TraceParser: one method per command; a strip or fan is collected until its `end`
//   and emitted as one CmdPrimitives whose SourceLoc is its first vertex's line.
// - Coordinates go through Q64::parse_decimal so the scene holds the exact decimal
//   value (round to odd), never a double that setup would round a second time.
// - Every malformed input ends in a SceneError; nothing here indexes past a token list
//   or trusts a number's size before checking it.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include "ref/scene.h"
#include "scene/scene_text.h"
#include "scene/scene_io.h"

namespace rastsim {



namespace {

using scene_text::quote;
using scene_text::Tokens;

// Largest viewport or scissor coordinate a trace may name: far beyond any framebuffer
// the config accepts, small enough that x + width never overflows an int.
constexpr int64_t kMaxExtent = 16384;

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
    // strip/fan it interrupts (that is emitted at `end`), so it may not appear inside one.
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
        {"end", &TraceParser::end, false}};
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
    return std::move(scene_);
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

  // `x y` (current colour and depth) or `x y z r g b` starting at t[i].
  SceneVertex vertex_at(const Tokens& t, size_t i, bool full, const std::string& label) const {
    SceneVertex v;
    v.x = coord(t[i], label + "x");
    v.y = coord(t[i + 1], label + "y");
    if (!full) {
      v.z = depth_;
      v.r = r_, v.g = g_, v.b = b_;
      return v;
    }
    v.z = unit(t[i + 2], label + "z");
    v.r = channel(t[i + 3], label + "red");
    v.g = channel(t[i + 4], label + "green");
    v.b = channel(t[i + 5], label + "blue");
    return v;
  }

  void emit(CommandBody body, int line) {
    scene_.commands.push_back({std::move(body), SourceLoc{name_, line}});
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
    for (size_t k = 0; k < 3; ++k)
      p.vertices.push_back(vertex_at(t, 1 + k * per, full, "vertex " + std::to_string(k) + " "));
    emit(std::move(p), line_);
  }

  void begin(const Tokens& t) {
    args(t, 0, "its vertices follow on 'v' lines up to 'end'");
    open_ = true;
    open_kw_ = std::string(t[0]);
    open_line_ = line_;
    first_vertex_line_ = 0;
    open_prims_ = CmdPrimitives{t[0] == "strip" ? Topology::Strip : Topology::Fan, {}};
  }

  void vertex(const Tokens& t) {
    if (!open_) fail("'v' outside a strip or fan");
    const size_t n = t.size() - 1;
    if (n != 2 && n != 6) fail("'v' takes 2 numbers (x y) or 6 (x y z r g b), got " + std::to_string(n));
    if (open_prims_.vertices.empty()) first_vertex_line_ = line_;
    open_prims_.vertices.push_back(vertex_at(t, 1, n == 6, ""));
  }

  void end(const Tokens& t) {
    if (!open_) fail("'end' without a 'strip' or 'fan'");
    args(t, 0, "none");
    const size_t n = open_prims_.vertices.size();
    if (n < 3) {
      line_ = open_line_;
      fail("'" + open_kw_ + "' has " + std::to_string(n) + " vertices; it needs at least 3");
    }
    open_ = false;
    emit(std::move(open_prims_), first_vertex_line_);
  }

  const std::string& name_;
  Scene scene_;
  int line_ = 0;
  uint8_t r_ = 255, g_ = 255, b_ = 255;  // `color`: white until set
  double depth_ = 0.0;                   // `depth`: nearest until set
  bool open_ = false;                    // inside strip/fan ... end
  std::string open_kw_;
  int open_line_ = 0, first_vertex_line_ = 0;
  CmdPrimitives open_prims_;
};

}  // namespace

Scene parse_trace(const std::string& text, const std::string& name) {
  TraceParser p(name);
  scene_text::for_each_line(text, name, [&](int line, const Tokens& t) { p.line(line, t); });
  return p.finish();
}

Scene load_trace(const std::string& path) { return parse_trace(scene_text::read_file(path), path); }

Scene load_scene(const std::string& path, const ObjPlacement& placement) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") return load_obj(path, placement);
  return load_trace(path);
}

}  // namespace rastsim
