// SPDX-License-Identifier: Apache-2.0
// Text layer shared by the trace and OBJ parsers: file reading (through scene_stream), line splitting with the
// NUL / line-length guards, '#' comments, whitespace tokens, strict number syntax, and
// the one "file:line: what" error builder.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <functional>
#include <limits>
#include <optional>
#include <string_view>

#include "scene/scene_stream.h"
#include "scene/scene_text.h"

namespace rastsim {

namespace scene_text {

// Longest line either format accepts (excluding the newline). A bound keeps error
// messages and per-line token lists small whatever a corrupted file holds.
constexpr size_t kMaxLineChars = 4096;

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw SceneError(file + ":" + std::to_string(line) + ": " + what);
}

// A token as it may appear in an error message: quoted, control and non-ASCII bytes
// escaped, long tokens cut, so a binary file cannot garble the terminal.
std::string quote(std::string_view tok) {
  constexpr size_t kMaxShown = 40;
  std::string out = "'";
  for (size_t i = 0; i < tok.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (tok.size() > kMaxShown) out += "...";
  return out + "'";
}

// Whole file as text, decompressed when it is gzip or zstd (scene_stream.h checks that
// it is a regular file and bounds its size).
std::string read_file(const std::string& path) { return scene_stream::read_all(path); }

namespace {

// One line (without its '\n'): the guards, comment stripping, tokens, fn.
void one_line(std::string_view s, int line, const std::string& name, Tokens& tokens, const LineFn& fn) {
  if (s.size() > kMaxLineChars)
    fail(name, line, "line is longer than " + std::to_string(kMaxLineChars) + " characters");
  if (std::memchr(s.data(), '\0', s.size()) != nullptr) fail(name, line, "NUL byte (not a text file?)");
  // Tokens split on " \t\r\v\f", up to a '#' (which also ends a token): one pass over
  // the characters (find_first_of with a set searched the set once a character, and was
  // a tenth of reading a trace of small triangles).
  tokens.clear();
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  const char* p = s.data();
  const char* const end = p + s.size();
  for (;;) {
    while (p != end && space(*p)) ++p;
    if (p == end || *p == '#') break;
    const char* const b = p;
    while (p != end && !space(*p) && *p != '#') ++p;
    tokens.emplace_back(b, size_t(p - b));
  }
  if (!tokens.empty()) fn(line, tokens);
}

// A UTF-8 byte-order mark, which some editors write at the start of a text file (the
// TOML reader accepts it too): skipped there, never taken as a token.
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

size_t after_bom(std::string_view text) { return text.substr(0, kUtf8Bom.size()) == kUtf8Bom ? kUtf8Bom.size() : 0; }

// The complete lines of `text` from `pos`; returns where the unfinished last line starts.
size_t complete_lines(std::string_view text, size_t pos, int& line, const std::string& name, Tokens& tokens,
                      const LineFn& fn) {
  for (size_t eol; (eol = text.find('\n', pos)) != std::string_view::npos; pos = eol + 1) {
    if (line == std::numeric_limits<int>::max()) fail(name, line, "too many lines");
    one_line(text.substr(pos, eol - pos), ++line, name, tokens, fn);
  }
  return pos;
}

}  // namespace

// Calls fn(line, tokens) for every line that has a token after comment stripping;
// returns the number of lines. Lines split on '\n'; '\r' counts as whitespace, so
// CRLF files read the same as LF files.
int for_each_line(std::string_view text, const std::string& name, const LineFn& fn) {
  int line = 0;
  Tokens tokens;
  const size_t rest = complete_lines(text, after_bom(text), line, name, tokens, fn);
  if (rest < text.size()) {
    if (line == std::numeric_limits<int>::max()) fail(name, line, "too many lines");
    one_line(text.substr(rest), ++line, name, tokens, fn);
  }
  return line;
}

int for_each_line(scene_stream::Reader& in, const std::string& name, const LineFn& fn) {
  constexpr size_t kChunk = size_t{1} << 20;
  std::string buf;  // an unfinished line carried over, then the next chunk
  int line = 0;
  bool bom_checked = false;
  Tokens tokens;
  for (;;) {
    const size_t kept = buf.size();
    buf.resize(kept + kChunk);
    const size_t got = in.read(buf.data() + kept, kChunk);
    buf.resize(kept + got);
    if (got == 0) break;
    if (!bom_checked) {  // the mark can only start the file; a shorter start may still be one
      if (buf.size() < kUtf8Bom.size() && kUtf8Bom.substr(0, buf.size()) == buf) continue;
      buf.erase(0, after_bom(buf));
      bom_checked = true;
    }
    const size_t rest = complete_lines(buf, 0, line, name, tokens, fn);
    buf.erase(0, rest);
    // An unfinished line already too long fails now, not after reading the rest of it.
    if (buf.size() > kMaxLineChars) one_line(buf, line + 1, name, tokens, fn);
  }
  if (!buf.empty()) {
    if (line == std::numeric_limits<int>::max()) fail(name, line, "too many lines");
    one_line(buf, ++line, name, tokens, fn);
  }
  return line;
}

// A whole token as a T through from_chars, which reads an optional '-' but not '+'
// (exporters write both): no spaces, no "+-", no trailing garbage, no hex.
template <class T>
std::optional<T> from_token(std::string_view tok) {
  if (!tok.empty() && tok[0] == '+') {
    tok.remove_prefix(1);
    if (!tok.empty() && tok[0] == '-') return std::nullopt;
  }
  T v{};
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (tok.empty() || r.ec != std::errc() || r.ptr != tok.data() + tok.size()) return std::nullopt;
  return v;
}

std::optional<int64_t> parse_int(std::string_view tok) { return from_token<int64_t>(tok); }

// A finite double in the usual exporter syntax (1, -0.5, 1e-3); no inf or nan. Values
// beyond the double range (1e999, and 1e-999 below it) are errors too.
std::optional<double> parse_double(std::string_view tok) {
  const auto v = from_token<double>(tok);
  if (v && !std::isfinite(*v)) return std::nullopt;
  return v;
}

// libstdc++'s from_chars<float> (GCC 12) rounds the exact decimal value once, to
// nearest even, straight to binary32 (no detour through double, which could round
// twice), and gives denormals; it reports result_out_of_range both for a value past the
// largest binary32 (at or over 2^128 - 2^103, which rounds to infinity) and for one that
// rounds to zero (below half the smallest denormal, 2^-150, or exactly half: ties to
// even). The second is the correctly rounded +-0, not an error: told apart by the
// exponent of the same text read as a long double (whose range holds both cases).
ParsedFloat parse_float(std::string_view tok) {
  const bool plus = !tok.empty() && tok[0] == '+';  // exporters write it; from_chars does not read it
  const std::string_view body = plus ? tok.substr(1) : tok;
  if (body.empty() || (plus && body[0] == '-')) return {FloatStatus::Malformed, 0.0f};
  float v = 0.0f;
  const auto r = std::from_chars(body.data(), body.data() + body.size(), v);
  if (r.ptr != body.data() + body.size() || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range))
    return {FloatStatus::Malformed, 0.0f};
  if (r.ec == std::errc::result_out_of_range) {
    const std::string text(body);  // strtold needs the terminating NUL
    const long double wide = std::strtold(text.c_str(), nullptr);
    if (std::fabs(wide) > 1.0L) return {FloatStatus::Overflow, 0.0f};
    return {FloatStatus::Ok, body[0] == '-' ? -0.0f : 0.0f};
  }
  if (!std::isfinite(v)) return {FloatStatus::NotFinite, 0.0f};
  return {FloatStatus::Ok, v};
}

}  // namespace scene_text

}  // namespace rastsim
