// SPDX-License-Identifier: Apache-2.0
// One call of `apitrace dump --multiline=no --blobs` text, parsed: the call number, the
// function's name, its named arguments and its return value (docs/workloads.md,
// "Importing an apitrace capture"). apitrace prints one call a line in that mode:
//   2496 glDrawArrays(mode = GL_TRIANGLES, first = 0, count = 21516)
//   2455 glCreateProgram() = 1
//   2476 glBufferData(target = GL_ARRAY_BUFFER, size = 12, data = blob("blob_call2476.bin"), ...)
//   2457 glShaderSource(shader = 2, count = 1, string = &"line\nline", length = NULL)
//   1270 glViewport(x = 0, y = 0, width = 160, height = 120) // fake
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rastsim::apitrace {

// A value as apitrace prints it. Scalar: a number, an enum (GL_TRIANGLES), an enum
// expression (GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT), NULL, True, an address: the
// text as printed. String: the unescaped bytes. List: {a, b, ...}. Blob: the file name
// `--blobs` wrote the bytes to. A pointer (&x) is x.
struct Value {
  enum class Kind { Scalar, String, List, Blob };
  Kind kind = Kind::Scalar;
  std::string text;
  std::vector<Value> items;
};

struct Arg {
  std::string name;
  Value value;
};

struct Call {
  uint64_t number = 0;
  std::string function;
  std::vector<Arg> args;
  std::optional<Value> ret;
  bool fake = false;  // "// fake": a call apitrace made up at capture (window size)
  int line = 0;       // line of the dump text

  // The argument of that name, or nullptr.
  const Value* arg(std::string_view name) const;
};

// Parses one line. Returns nullopt for lines that are not calls (blank, "// comment",
// the second line of a call that returned nothing); throws SceneError("name:line: what")
// for a line that starts with a call number but cannot be read.
std::optional<Call> parse_call_line(std::string_view line, const std::string& name, int line_no);

// A scalar's value as a number: decimal or 0x hex integer, or a decimal/exponent float;
// nullopt when it is none of these (an enum, NULL, a list).
std::optional<double> number(const Value& v);
std::optional<int64_t> integer(const Value& v);

}  // namespace rastsim::apitrace
