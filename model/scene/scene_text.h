// SPDX-License-Identifier: Apache-2.0
// Text layer shared by the trace and OBJ parsers (scene_trace.cpp, scene_obj.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ref/scene.h"
#include "scene/scene_stream.h"

namespace rastsim::scene_text {

using Tokens = std::vector<std::string_view>;
using LineFn = std::function<void(int line, const Tokens& tokens)>;

// Throws SceneError("file:line: what").
[[noreturn]] void fail(const std::string& file, int line, const std::string& what);
// A token as it appears in an error: quoted, control bytes escaped, long tokens cut.
std::string quote(std::string_view tok);
// Whole file, decompressed if gzip or zstd (scene_stream.h); SceneError "path: ..." otherwise.
std::string read_file(const std::string& path);
// Calls fn(line, tokens) for every non-blank line with '#' comments removed; rejects NUL
// bytes and overlong lines. Returns the number of lines.
int for_each_line(std::string_view text, const std::string& name, const LineFn& fn);
// The same reading the file chunk by chunk (memory: one chunk and one line).
int for_each_line(scene_stream::Reader& in, const std::string& name, const LineFn& fn);
// Strict numbers: the whole token, nothing else; nullopt when malformed or not finite.
std::optional<int64_t> parse_int(std::string_view tok);
std::optional<double> parse_double(std::string_view tok);

// A decimal (or exponent) number as IEEE binary32, rounded to nearest even once from the
// exact decimal value (what a vertex stage hands over): a value or why not.
enum class FloatStatus { Ok, Malformed, NotFinite, Overflow };
struct ParsedFloat {
  FloatStatus status = FloatStatus::Malformed;
  float value = 0.0f;
};
ParsedFloat parse_float(std::string_view tok);

}  // namespace rastsim::scene_text
