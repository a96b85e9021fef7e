// SPDX-License-Identifier: Apache-2.0
// Recorded video signal (VCD, or FST through fst2vcd) -> VideoSample stream (see signal_reader.h).
#include "display/signal_reader.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <unordered_map>

#include "util/process.h"

namespace rastsim {

namespace {

// `what` as it may reach a terminal: the bytes of a random or binary file (control bytes,
// non-ASCII, an escape sequence) as \xNN, and cut after kMaxShown bytes, so a message
// quoting a token of such a file is plain text of a line.
std::string printable(std::string_view what) {
  constexpr size_t kMaxShown = 300;
  static const char* const hex = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < what.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(what[i]);
    if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
    else out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
  }
  return what.size() > kMaxShown ? out + "..." : out;
}

}  // namespace

SignalFileError::SignalFileError(const std::string& file, long long line, const std::string& what)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + printable(what)),
      file_(file), line_(line) {}

namespace {

// Roles of the variables the reader uses.
enum Role { kHsync, kVsync, kBlank, kDe, kCodeR, kCodeG, kCodeB, kLevelR, kLevelG, kLevelB, kClock, kRoles };
const char* const kRoleName[kRoles] = {"hsync",  "vsync",   "blank",   "de",      "code_r", "code_g",
                                       "code_b", "level_r", "level_g", "level_b", "clock"};

// Role of a variable from its name (lower case, no range, `_o` dropped); -1 = none.
int role_of(std::string n) {
  if (n.size() > 2 && n.compare(n.size() - 2, 2, "_o") == 0) n.resize(n.size() - 2);
  static const std::unordered_map<std::string, int> names = {
      {"hsync", kHsync},    {"hs", kHsync},       {"vsync", kVsync},       {"vs", kVsync},
      {"blank", kBlank},    {"de", kDe},          {"data_enable", kDe},    {"code_r", kCodeR},
      {"dac_r", kCodeR},    {"code_g", kCodeG},   {"dac_g", kCodeG},       {"code_b", kCodeB},
      {"dac_b", kCodeB},    {"level_r", kLevelR}, {"level_g", kLevelG},    {"level_b", kLevelB},
      {"clk", kClock},      {"clk_i", kClock},    {"pclk", kClock},        {"pixel_clk", kClock},
      {"clk_pixel", kClock}};
  auto it = names.find(n);
  return it == names.end() ? -1 : it->second;
}

// A sample count for a message: "1.2e+13" style, enough digits to tell values apart.
std::string fmt_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string lower(std::string_view s) {
  std::string o(s);
  for (char& c : o) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return o;
}

// Whitespace-separated tokens with their line numbers (VCD is token-, not line-based).
class Lexer {
 public:
  explicit Lexer(std::istream& in) : in_(in) {}
  // The next token (valid until the next call), false at the end of the input.
  bool next(std::string_view& tok) {
    for (;;) {
      while (pos_ < buf_.size() && std::isspace(static_cast<unsigned char>(buf_[pos_]))) ++pos_;
      if (pos_ < buf_.size()) {
        const size_t b = pos_;
        while (pos_ < buf_.size() && !std::isspace(static_cast<unsigned char>(buf_[pos_]))) ++pos_;
        tok = std::string_view(buf_).substr(b, pos_ - b);
        tok_line_ = line_;
        return true;
      }
      if (!std::getline(in_, buf_)) return false;
      ++line_, pos_ = 0;
    }
  }
  long long line() const { return tok_line_; }  // line of the last token
  long long lines_read() const { return line_; }

 private:
  std::istream& in_;
  std::string buf_;
  size_t pos_ = 0;
  long long line_ = 0, tok_line_ = 0;
};

struct Var {
  std::string id, full_name, name;  // name: last component, lower case, no range
  int depth = 0, width = 1;
  bool real = false;
  long long line = 0;
};

struct Value {
  uint64_t bits = 0;
  double real = 0;
  bool unknown = true;  // x or z (VCD variables start as x)
};

class Reader {
 public:
  Reader(std::istream& in, const std::string& name, const VideoTiming& t, const Dac& dac, const SampleSink& sink,
         const SignalReaderOptions& o)
      : lex_(in), name_(name), t_(t), dac_(dac), sink_(sink), opts_(o) {}

  SignalReadInfo run() {
    header();
    choose_roles();
    body();
    finish();
    return std::move(info_);
  }

 private:
  [[noreturn]] void fail(const std::string& what, long long line = -1) const {
    throw SignalFileError(name_, line < 0 ? lex_.line() : line, what);
  }
  bool next(std::string_view& tok) { return lex_.next(tok); }
  // Tokens up to $end of the section `kw` opened on `opened`.
  std::vector<std::string> section(std::string_view kw, long long opened) {
    std::vector<std::string> toks;
    std::string_view tok;
    for (;;) {
      if (!next(tok))
        fail(std::string(kw) + " (opened here) is not closed by $end before the end of the file", opened);
      if (tok == "$end") return toks;
      if (tok.size() > 1 && tok[0] == '$')
        fail("'" + std::string(tok) + "' inside " + std::string(kw) + " (opened on line " + std::to_string(opened) +
             "): a $end is missing");
      toks.emplace_back(tok);
    }
  }

  // ---- declarations ----
  void header() {
    std::string_view tok;
    std::vector<std::string> scope;
    for (;;) {
      if (!next(tok))
        fail(lex_.lines_read() == 0 ? "empty file: not a VCD"
                                    : "end of the file before $enddefinitions: not a complete VCD header",
             lex_.lines_read());
      const long long at = lex_.line();
      const std::string kw(tok);
      if (kw == "$date" || kw == "$version" || kw == "$comment") {
        skip_to_end(kw, at);
      } else if (kw == "$timescale") {
        timescale(section(kw, at), at);
      } else if (kw == "$scope") {
        auto s = section(kw, at);
        if (s.size() != 2) fail("$scope: expected a scope type and a name, e.g. '$scope module top $end'", at);
        scope.push_back(s[1]);
      } else if (kw == "$upscope") {
        if (!section(kw, at).empty()) fail("$upscope takes no arguments", at);
        if (scope.empty()) fail("$upscope without an open $scope", at);
        scope.pop_back();
      } else if (kw == "$var") {
        var(section(kw, at), scope, at);
      } else if (kw == "$enddefinitions") {
        section(kw, at);
        if (!scope.empty()) fail("$enddefinitions with $scope " + scope.back() + " still open", at);
        if (vars_.empty()) fail("no $var declarations", at);
        if (ts_s_ == 0) ts_s_ = 1e-12, info_.timescale = "1ps (none declared; the VCD default)";
        enddefs_line_ = at;
        return;
      } else {
        fail("'" + kw + "' in the header: expected $timescale, $scope, $var, $upscope, $enddefinitions, ...", at);
      }
    }
  }
  void skip_to_end(const std::string& kw, long long at) {  // free text up to $end
    std::string_view tok;
    for (;;) {
      if (!next(tok)) fail(kw + " (opened here) is not closed by $end before the end of the file", at);
      if (tok == "$end") return;
    }
  }
  void timescale(const std::vector<std::string>& toks, long long at) {
    std::string s;
    for (auto& x : toks) s += x;
    size_t i = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    const std::string num = s.substr(0, i), unit = s.substr(i);
    static const std::map<std::string, double> units = {{"s", 1},     {"ms", 1e-3},  {"us", 1e-6},
                                                        {"ns", 1e-9}, {"ps", 1e-12}, {"fs", 1e-15}};
    auto u = units.find(unit);
    if ((num != "1" && num != "10" && num != "100") || u == units.end())
      fail("$timescale: expected 1, 10 or 100 and a unit (s, ms, us, ns, ps, fs), got '" + s + "'", at);
    ts_s_ = std::stod(num) * u->second;
    info_.timescale = s;
  }
  void var(const std::vector<std::string>& f, const std::vector<std::string>& scope, long long at) {
    if (f.size() < 4) fail("$var: expected 'type width identifier name [range]', got " + std::to_string(f.size()) + " fields", at);
    Var v;
    v.real = f[0] == "real" || f[0] == "realtime";
    char* end = nullptr;
    errno = 0;
    const long w = std::strtol(f[1].c_str(), &end, 10);
    if (*end || w < 1) fail("$var: width '" + f[1] + "' is not a positive number", at);
    // Widths are ints here; a larger one would wrap to another width, never read as itself.
    if (w > INT_MAX || errno == ERANGE)
      fail("$var: width '" + f[1] + "' is more than " + std::to_string(INT_MAX) + " bits", at);
    v.width = static_cast<int>(w);
    v.id = f[2];
    std::string n = f[3];
    if (auto b = n.find('['); b != std::string::npos && b > 0) n.resize(b);  // "code_r[7:0]"
    v.name = lower(n);
    for (auto& s : scope) v.full_name += s + ".";
    v.full_name += n;
    v.depth = static_cast<int>(scope.size());
    v.line = at;
    auto [it, added] = slot_.emplace(v.id, static_cast<int>(values_.size()));
    if (added) values_.emplace_back(), slot_real_.push_back(v.real), slot_width_.push_back(v.width);
    vars_.push_back(std::move(v));
  }

  void choose_roles() {
    role_slot_.fill(-1);
    std::array<const Var*, kRoles> best{};
    const std::string want_clock = lower(opts_.clock);
    for (const Var& v : vars_) {
      int r = role_of(v.name);
      if (!want_clock.empty()) {  // the clock is the one named, or none
        if (r == kClock) r = -1;
        if (want_clock != "none" && (lower(v.full_name) == want_clock || v.name == want_clock)) r = kClock;
      }
      if (r < 0) continue;
      if (r == kClock && (v.real || v.width != 1)) continue;
      if (!best[r] || v.depth < best[r]->depth) best[r] = &v;
    }
    if (!want_clock.empty() && want_clock != "none" && !best[kClock])
      fail("no 1-bit variable named '" + opts_.clock + "' for the clock", enddefs_line_);
    for (int r = 0; r < kRoles; ++r)
      if (best[r]) {
        role_slot_[r] = slot_.at(best[r]->id);
        info_.variables[kRoleName[r]] = best[r]->full_name;
        const bool want_real = r >= kLevelR && r <= kLevelB;
        if (best[r]->real != want_real)
          fail(best[r]->full_name + " is declared " + (best[r]->real ? "real" : "as bits") + ", expected " +
               (want_real ? "a real (volts)" : "bits"), best[r]->line);
      }
    auto missing = [&](int r, const char* names) {
      if (role_slot_[r] < 0) fail(std::string("no ") + kRoleName[r] + " variable among the $var declarations (names tried: " + names + ")", enddefs_line_);
    };
    missing(kHsync, "hsync, hsync_o, hs");
    missing(kVsync, "vsync, vsync_o, vs");
    if (role_slot_[kBlank] < 0 && role_slot_[kDe] < 0)
      fail("no blank variable among the $var declarations (names tried: blank, blank_o, or de, data_enable)", enddefs_line_);
    const int nlev = (role_slot_[kLevelR] >= 0) + (role_slot_[kLevelG] >= 0) + (role_slot_[kLevelB] >= 0);
    const int ncode = (role_slot_[kCodeR] >= 0) + (role_slot_[kCodeG] >= 0) + (role_slot_[kCodeB] >= 0);
    if (nlev == 3) {
      use_levels_ = true;
      info_.levels_from = "level_r/g/b";
    } else if (ncode == 3) {
      info_.levels_from = "code_r/g/b through the DAC";
    } else {
      fail("no complete set of levels (level_r, level_g, level_b: reals) or codes (code_r/dac_r, ...: vectors): found " +
           std::to_string(nlev) + " levels and " + std::to_string(ncode) + " codes", enddefs_line_);
    }
    if (!use_levels_)
      for (int r = kCodeR; r <= kCodeB; ++r)
        if (slot_width_[role_slot_[r]] != dac_.config().bits)
          info_.problems.push_back(info_.variables[kRoleName[r]] + " is " + std::to_string(slot_width_[role_slot_[r]]) +
                                   " bits wide, but the DAC (dac.bits) has " + std::to_string(dac_.config().bits) +
                                   ": the levels from these codes are wrong");
    if (role_slot_[kClock] >= 0) {
      info_.clock = info_.variables["clock"];
    } else {
      if (!(t_.pixel_clock_hz > 0)) fail("the expected timing has no pixel clock to sample at", 0);
      period_ = 1.0 / (t_.pixel_clock_hz * ts_s_);
      info_.sample_clock_hz = t_.pixel_clock_hz;
    }
  }

  // ---- value changes ----
  void body() {
    std::string_view tok;
    int dump_depth = 0;  // inside $dumpvars / $dumpall / $dumpon / $dumpoff
    while (next(tok)) {
      const char c = tok[0];
      if (c == '#') {
        timestamp(tok);
      } else if (c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z') {
        if (tok.size() < 2) fail("scalar value change '" + std::string(tok) + "' has no identifier");
        Value& v = value_of(tok.substr(1), false, 1);
        v.unknown = c != '0' && c != '1';
        v.bits = c == '1';
      } else if (c == 'b' || c == 'B') {
        const std::string val(tok.substr(1));
        const long long at = lex_.line();
        if (!next(tok)) fail("vector value change '" + std::string(1, c) + val + "' has no identifier", at);
        Value& v = value_of(tok, false, static_cast<int>(val.size()));
        if (val.empty()) fail("vector value change with no bits");
        v.bits = 0, v.unknown = false;
        for (char b : val) {
          if (b != '0' && b != '1' && b != 'x' && b != 'X' && b != 'z' && b != 'Z')
            fail("vector value 'b" + val + "': '" + std::string(1, b) + "' is not 0, 1, x or z");
          // 64 bits hold every code the DAC takes (dac.bits <= 10); a set bit shifted out of
          // a wider value saturates it, so it reads as over range (clamped and reported),
          // never as the small number its low 64 bits spell.
          v.bits = v.bits >> 63 ? ~uint64_t{0} : (v.bits << 1 | (b == '1'));
          v.unknown |= b != '0' && b != '1';
        }
      } else if (c == 'r' || c == 'R') {
        const std::string val(tok.substr(1));
        const long long at = lex_.line();
        if (!next(tok)) fail("real value change 'r" + val + "' has no identifier", at);
        Value& v = value_of(tok, true, 0);
        char* end = nullptr;
        errno = 0;
        const double d = std::strtod(val.c_str(), &end);
        if (val.empty() || *end || errno == ERANGE) fail("real value 'r" + val + "' is not a number", at);
        v.real = d, v.unknown = !std::isfinite(d);
      } else if (tok == "$dumpvars" || tok == "$dumpall" || tok == "$dumpon" || tok == "$dumpoff") {
        ++dump_depth;
      } else if (tok == "$end") {
        if (dump_depth-- == 0) fail("$end without an open $dumpvars/$dumpall/$dumpon/$dumpoff");
      } else if (tok == "$comment") {
        skip_to_end("$comment", lex_.line());
      } else {
        fail("'" + std::string(tok) + "' is not a value change (0/1/x/z, b..., r...), a timestamp (#...) or a $dump section");
      }
    }
    if (dump_depth > 0) fail("a $dump section is not closed by $end before the end of the file", lex_.lines_read());
    if (!have_time_) fail("no timestamps (#...) after $enddefinitions: nothing to sample", lex_.lines_read());
  }
  Value& value_of(std::string_view id, bool real, int width) {
    auto it = slot_.find(std::string(id));
    if (it == slot_.end()) fail("value change for identifier '" + std::string(id) + "', which no $var declares");
    if (slot_real_[it->second] != real)
      fail(std::string(real ? "real" : "bit") + " value for identifier '" + std::string(id) + "', declared as " +
           (slot_real_[it->second] ? "real" : "bits"));
    if (!real && width > slot_width_[it->second])
      fail("value of " + std::to_string(width) + " bits for identifier '" + std::string(id) + "', declared " +
           std::to_string(slot_width_[it->second]) + " bits wide");
    return values_[it->second];
  }
  void timestamp(std::string_view tok) {
    const std::string s(tok.substr(1));
    char* end = nullptr;
    errno = 0;
    const long long T = std::strtoll(s.c_str(), &end, 10);
    if (s.empty() || *end || T < 0 || errno == ERANGE) fail("timestamp '" + std::string(tok) + "' is not a non-negative integer");
    if (have_time_ && T < now_)
      fail("timestamp #" + s + " goes back in time (the previous one is #" + std::to_string(now_) + ")");
    if (have_time_ && T == now_) return;  // same time again: keep collecting its changes
    end_block();
    if (!have_time_) t0_ = T, have_time_ = true;
    // Without a clock: every sample strictly before T sees the values up to now.
    if (period_ > 0) {
      // A video signal changes every line (hsync), so a gap of more than a frame without
      // a change is no recording of one; replaying it would take time and memory out of
      // all proportion to the file (#9223372036854775807 is ~10^13 frames at 1 ps).
      const double gap = (double(T) - double(t0_)) / period_ - 0.5 - double(k_);
      const long long frame = std::max(t_.pixels_per_frame(), 1LL);
      if (gap > double(frame))
        fail("timestamp #" + s + " is " + fmt_g(gap) + " pixel clocks after the previous one (#" +
             std::to_string(now_) + "): more than a frame (" + std::to_string(frame) +
             " pixel clocks) without a value change, where hsync changes every line");
      const RoleState st = roles();
      while (t0_ + (k_ + 0.5) * period_ < double(T)) emit(st);
    }
    now_ = T;
    if (role_slot_[kClock] >= 0) block_start_ = roles();  // the values just before this time's changes
  }
  using RoleState = std::array<Value, kRoles>;
  RoleState roles() const {
    RoleState st{};
    for (int r = 0; r < kRoles; ++r)
      if (role_slot_[r] >= 0) st[r] = values_[role_slot_[r]];
    return st;
  }
  static bool high(const Value& v) { return !v.unknown && (v.bits & 1); }
  // The changes at `now_` are complete: a rising clock edge samples the values before it.
  void end_block() {
    if (!have_time_ || role_slot_[kClock] < 0) return;
    const Value& before = block_start_[kClock];
    if (!before.unknown && !high(before) && high(values_[role_slot_[kClock]])) {
      if (edges_++ == 0) first_edge_ = now_;
      else emit(block_start_);
      last_edge_ = now_;
    }
  }

  void emit(const RoleState& v) {
    const long long i = k_++;
    VideoSample s;
    auto bit = [&](int r) {
      const Value& x = v[r];
      if (x.unknown && unknown_[r]++ == 0) first_unknown_[r] = i;
      return !x.unknown && (x.bits & 1);
    };
    s.hsync = bit(kHsync);
    s.vsync = bit(kVsync);
    s.blank = role_slot_[kBlank] >= 0 ? bit(kBlank) : !bit(kDe);
    for (int c = 0; c < 3; ++c) {
      if (role_slot_[kCodeR + c] >= 0) {
        const Value& x = v[kCodeR + c];
        if (x.unknown && !use_levels_ && unknown_[kCodeR + c]++ == 0) first_unknown_[kCodeR + c] = i;
        uint64_t code = x.bits;
        if (code > uint64_t(dac_.max_code())) {
          if (over_range_++ == 0) first_over_range_ = i;
          code = dac_.max_code();
        }
        s.code[c] = static_cast<uint16_t>(code);
      }
      if (use_levels_) {
        const Value& x = v[kLevelR + c];
        if (x.unknown && unknown_[kLevelR + c]++ == 0) first_unknown_[kLevelR + c] = i;
        s.volts[c] = static_cast<float>(x.real);
      } else {
        s.volts[c] = s.blank ? 0.f : static_cast<float>(dac_.volts(c, s.code[c]));
      }
    }
    sink_(s);
  }

  void finish() {
    end_block();
    if (role_slot_[kClock] >= 0) {
      if (edges_ < 2)
        fail("the clock " + info_.clock + " has " + std::to_string(edges_) +
             " rising edges: nothing to sample (choose another clock, or none to sample at the expected pixel clock)", 0);
      const double period = double(last_edge_ - first_edge_) / (edges_ - 1);
      if (double(now_ - last_edge_) >= period / 2) emit(roles());
      info_.sample_clock_hz = 1.0 / (period * ts_s_);
      const double rel = info_.sample_clock_hz / t_.pixel_clock_hz - 1;
      if (t_.pixel_clock_hz > 0 && std::abs(rel) > 1e-3) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "the clock %s runs at %.6g MHz (timescale %s), the expected mode's pixel clock is %.6g MHz; "
                      "rates are reported at the expected pixel clock",
                      info_.clock.c_str(), info_.sample_clock_hz / 1e6, info_.timescale.c_str(), t_.pixel_clock_hz / 1e6);
        info_.notes.push_back(buf);
      }
    }
    info_.samples = k_;
    for (int r = 0; r < kRoles; ++r)
      if (unknown_[r])
        info_.problems.push_back(info_.variables[kRoleName[r]] + " is x or z at " + std::to_string(unknown_[r]) + " of " +
                                 std::to_string(k_) + " sampled pixel clocks (first at clock " +
                                 std::to_string(first_unknown_[r]) + "), read as 0");
    if (over_range_)
      info_.problems.push_back("codes above the DAC's " + std::to_string(dac_.max_code()) + " at " +
                               std::to_string(over_range_) + " samples (first at clock " +
                               std::to_string(first_over_range_) + "), clamped");
  }

  Lexer lex_;
  const std::string name_;
  const VideoTiming& t_;
  const Dac& dac_;
  const SampleSink& sink_;
  const SignalReaderOptions& opts_;
  SignalReadInfo info_;
  double ts_s_ = 0;
  long long enddefs_line_ = 0;
  std::vector<Var> vars_;
  std::unordered_map<std::string, int> slot_;  // identifier -> value slot
  std::vector<Value> values_;
  std::array<Value, kRoles> block_start_{};
  std::vector<bool> slot_real_;
  std::vector<int> slot_width_;
  std::array<int, kRoles> role_slot_{};
  bool use_levels_ = false;
  // Sampling.
  double period_ = 0;  // in time units; 0 = on the clock variable
  bool have_time_ = false;
  long long t0_ = 0, now_ = 0, k_ = 0;
  long long edges_ = 0, first_edge_ = 0, last_edge_ = 0;
  std::array<long long, kRoles> unknown_{}, first_unknown_{};
  long long over_range_ = 0, first_over_range_ = 0;
};

}  // namespace

SignalReadInfo read_video_vcd(std::istream& in, const std::string& name, const VideoTiming& expected, const Dac& dac,
                              const SampleSink& sink, const SignalReaderOptions& opts) {
  return Reader(in, name, expected, dac, sink, opts).run();
}

SignalReadInfo read_video_signal(const std::string& path, const VideoTiming& expected, const Dac& dac,
                                 const SampleSink& sink, const SignalReaderOptions& opts) {
  const bool fst = path.size() > 4 && lower(path.substr(path.size() - 4)) == ".fst";
  // A recording is a file of a known length: a device or pipe (/dev/zero, /dev/urandom)
  // may never end, and the reader would hold its "line" in memory until none is left.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw SignalFileError(path, 0, "not a regular file (a device, pipe or directory): the monitor reads a recorded "
                                   ".vcd or .fst file");
  if (!fst) {
    std::ifstream in(path);
    if (!in) throw SignalFileError(path, 0, "cannot open for reading");
    return read_video_vcd(in, path, expected, dac, sink, opts);
  }
  if (!std::ifstream(path)) throw SignalFileError(path, 0, "cannot open for reading");
  if (find_program("fst2vcd").empty())
    throw SignalFileError(path, 0, "reading .fst needs fst2vcd (Debian package gtkwave); or record a .vcd");
  std::string tmp = (std::filesystem::temp_directory_path() / "rastsim_signal_XXXXXX").string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0) throw SignalFileError(path, 0, "cannot create a temporary file for fst2vcd");
  close(fd);
  struct Remove {
    std::string p;
    ~Remove() { std::remove(p.c_str()); }
  } remove_tmp{tmp};
  ProcessOptions quiet;
  quiet.out = quiet.err = Sink::Null;
  if (!run_process({"fst2vcd", "-f", path, "-o", tmp}, quiet).ok())
    throw SignalFileError(path, 0, "fst2vcd failed: not an FST file?");
  std::ifstream in(tmp);
  if (!in) throw SignalFileError(path, 0, "cannot read fst2vcd's output");
  return read_video_vcd(in, path + " (as VCD from fst2vcd)", expected, dac, sink, opts);
}

}  // namespace rastsim
