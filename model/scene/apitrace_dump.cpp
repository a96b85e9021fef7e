// SPDX-License-Identifier: Apache-2.0
#include "scene/apitrace_dump.h"

#include <cctype>
#include <charconv>
#include <cstdlib>

#include "ref/scene.h"
#include "scene/scene_text.h"

namespace rastsim::apitrace {

const Value* Call::arg(std::string_view name) const {
  for (const Arg& a : args)
    if (a.name == name) return &a.value;
  return nullptr;
}

namespace {

// A cursor over one line; every failure names the line and the column.
struct Cursor {
  std::string_view s;
  size_t pos = 0;
  const std::string& name;
  int line;

  [[noreturn]] void fail(const std::string& what) const {
    scene_text::fail(name, line, what + " (column " + std::to_string(pos + 1) + ")");
  }
  void skip_space() {
    while (pos < s.size() && s[pos] == ' ') ++pos;
  }
  bool eat(char c) {
    skip_space();
    if (pos < s.size() && s[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  bool starts(std::string_view p) const { return s.substr(pos, p.size()) == p; }
};

Value parse_value(Cursor& c);

// "..." with C escapes (apitrace writes \n, \t, \r, \", \\ and \ooo octal in this mode).
std::string parse_string(Cursor& c) {
  c.expect('"');
  std::string out;
  while (true) {
    if (c.pos >= c.s.size()) c.fail("unterminated string");
    const char ch = c.s[c.pos++];
    if (ch == '"') return out;
    if (ch != '\\') {
      out += ch;
      continue;
    }
    if (c.pos >= c.s.size()) c.fail("unterminated string");
    const char e = c.s[c.pos++];
    switch (e) {
      case 'n': out += '\n'; break;
      case 't': out += '\t'; break;
      case 'r': out += '\r'; break;
      case '"': out += '"'; break;
      case '\\': out += '\\'; break;
      default:
        if (e >= '0' && e <= '7') {
          int v = e - '0';
          for (int k = 0; k < 2 && c.pos < c.s.size() && c.s[c.pos] >= '0' && c.s[c.pos] <= '7'; ++k)
            v = v * 8 + (c.s[c.pos++] - '0');
          out += static_cast<char>(v);
        } else {
          out += e;  // \' \? and others stand for themselves
        }
    }
  }
}

Value parse_list(Cursor& c) {
  c.expect('{');
  Value v;
  v.kind = Value::Kind::List;
  if (c.eat('}')) return v;
  do {
    v.items.push_back(parse_value(c));
  } while (c.eat(','));
  c.expect('}');
  return v;
}

// A bare value: everything up to the next ',', ')' or '}' outside brackets.
Value parse_scalar(Cursor& c) {
  c.skip_space();
  const size_t start = c.pos;
  int depth = 0;
  while (c.pos < c.s.size()) {
    const char ch = c.s[c.pos];
    if (ch == '(' || ch == '[') ++depth;
    if ((ch == ')' || ch == ']') && depth > 0) {
      --depth;
    } else if (depth == 0 && (ch == ',' || ch == ')' || ch == '}')) {
      break;
    }
    ++c.pos;
  }
  size_t end = c.pos;
  while (end > start && c.s[end - 1] == ' ') --end;
  if (end == start) c.fail("missing value");
  Value v;
  v.text = std::string(c.s.substr(start, end - start));
  return v;
}

Value parse_value(Cursor& c) {
  c.skip_space();
  if (c.eat('&')) return parse_value(c);
  c.skip_space();
  if (c.pos >= c.s.size()) c.fail("missing value");
  if (c.s[c.pos] == '"') {
    Value v;
    v.kind = Value::Kind::String;
    v.text = parse_string(c);
    return v;
  }
  if (c.s[c.pos] == '{') return parse_list(c);
  if (c.starts("blob(")) {
    c.pos += 5;
    Value v;
    v.kind = Value::Kind::Blob;
    c.skip_space();
    if (c.pos < c.s.size() && c.s[c.pos] == '"') {
      v.text = parse_string(c);
    } else {
      c.fail("blob without a file name (dump with --blobs)");
    }
    c.expect(')');
    return v;
  }
  return parse_scalar(c);
}

void parse_args(Cursor& c, Call& call) {
  c.expect('(');
  if (c.eat(')')) return;
  do {
    c.skip_space();
    const size_t start = c.pos;
    while (c.pos < c.s.size() && (std::isalnum(static_cast<unsigned char>(c.s[c.pos])) || c.s[c.pos] == '_')) ++c.pos;
    if (c.pos == start) c.fail("expected an argument name");
    Arg a;
    a.name = std::string(c.s.substr(start, c.pos - start));
    c.expect('=');
    a.value = parse_value(c);
    call.args.push_back(std::move(a));
  } while (c.eat(','));
  c.expect(')');
}

}  // namespace

std::optional<Call> parse_call_line(std::string_view line, const std::string& name, int line_no) {
  if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) return std::nullopt;
  Cursor c{line, 0, name, line_no};
  Call call;
  call.line = line_no;
  const auto [p, ec] = std::from_chars(line.data(), line.data() + line.size(), call.number);
  if (ec != std::errc()) c.fail("bad call number");
  c.pos = static_cast<size_t>(p - line.data());
  if (c.pos >= line.size() || line[c.pos] != ' ') c.fail("expected a space after the call number");
  ++c.pos;
  const size_t start = c.pos;
  while (c.pos < line.size() && (std::isalnum(static_cast<unsigned char>(line[c.pos])) || line[c.pos] == '_')) ++c.pos;
  if (c.pos == start) c.fail("expected a function name after the call number");
  call.function = std::string(line.substr(start, c.pos - start));
  parse_args(c, call);
  if (c.eat('=')) call.ret = parse_value(c);
  c.skip_space();
  if (c.starts("// fake")) {
    call.fake = true;
  } else if (c.pos < line.size() && !c.starts("//")) {
    c.fail("unexpected text after the call");
  }
  return call;
}

std::optional<double> number(const Value& v) {
  if (v.kind != Value::Kind::Scalar || v.text.empty()) return std::nullopt;
  if (auto i = integer(v)) return static_cast<double>(*i);
  return scene_text::parse_double(v.text);
}

std::optional<int64_t> integer(const Value& v) {
  if (v.kind != Value::Kind::Scalar || v.text.empty()) return std::nullopt;
  const std::string& t = v.text;
  if (t == "NULL") return 0;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    uint64_t u = 0;
    const auto [p, ec] = std::from_chars(t.data() + 2, t.data() + t.size(), u, 16);
    if (ec != std::errc() || p != t.data() + t.size()) return std::nullopt;
    return static_cast<int64_t>(u);
  }
  return scene_text::parse_int(t);
}

}  // namespace rastsim::apitrace
