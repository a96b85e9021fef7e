// SPDX-License-Identifier: Apache-2.0
// Scene file bytes as a stream: plain, gzip or zstd, told apart by their magic bytes and
// decompressed incrementally, in chunks the caller sizes (docs/trace-format.md,
// "Compressed scenes").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace rastsim::scene_stream {

enum class Format { Plain, Gzip, Zstd };

// Most bytes a scene file may produce after decompression (4 GiB): far above any real
// scene (a 1,000,000-triangle trace is ~0.1 GiB), low enough that a decompression bomb
// stops with an error instead of exhausting memory. Plain files obey it too.
constexpr uint64_t kMaxSceneBytes = uint64_t{4} << 30;

// The format a file's first bytes announce: gzip 1f 8b, zstd 28 b5 2f fd, else Plain.
Format sniff(std::string_view head);
const char* format_name(Format f);
// ".gz" or ".zst" (any case) when the name ends in one, else empty.
std::string_view compression_suffix(std::string_view name);
// The name without its compression suffix: "a.trace.gz" -> "a.trace", "a.obj" -> "a.obj".
std::string strip_compression_suffix(std::string_view name);

// Reads a file's (decompressed) bytes chunk by chunk. Every error is a SceneError that
// starts with "path: ". A name with a compression suffix must hold data of a compressed
// format (a truncated-to-nothing or misnamed file is an error, not an empty text scene);
// any other name is read by what its magic bytes say.
class Reader {
 public:
  explicit Reader(const std::string& path, uint64_t max_bytes = kMaxSceneBytes);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  Format format() const;
  // Writes up to `cap` (> 0) decompressed bytes to `out`; returns how many. 0 means the
  // end of the data, reached only after a complete, checked stream.
  size_t read(char* out, size_t cap);
  // Decompressed bytes returned so far.
  uint64_t produced() const;

 private:
  struct Impl;  // the open file, its input chunk and the codec state
  std::unique_ptr<Impl> impl_;
};

// Every (decompressed) byte of the file, through Reader.
std::string read_all(const std::string& path, uint64_t max_bytes = kMaxSceneBytes);

}  // namespace rastsim::scene_stream
