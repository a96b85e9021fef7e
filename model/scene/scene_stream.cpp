// SPDX-License-Identifier: Apache-2.0
// Scene file bytes as a stream (scene_stream.h): the file is read in fixed 64 KiB input
// chunks and, when compressed, inflated (zlib) or decompressed (libzstd) straight into
// the caller's buffer, so nothing here holds more than one input chunk and the codec's
// own window (32 KiB for deflate, at most 128 MiB for zstd's default window limit).
//
// Error policy: a stream must end exactly at a complete, checked gzip member or zstd
// frame; anything else (truncation, a bad CRC or checksum, trailing garbage) is an
// error naming the file, never a silently shorter scene.
#include "scene/scene_stream.h"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <vector>

#include "ref/scene.h"

namespace rastsim::scene_stream {

namespace {

constexpr size_t kInputChunk = 64 * 1024;  // bytes read from the file per refill
// zlib counts in uInt (32 bits): one inflate call writes at most this many bytes.
constexpr size_t kMaxInflateOut = size_t{1} << 30;

constexpr std::array<unsigned char, 2> kGzipMagic = {0x1f, 0x8b};
constexpr std::array<unsigned char, 4> kZstdMagic = {0x28, 0xb5, 0x2f, 0xfd};

template <size_t N>
bool starts_with(std::string_view s, const std::array<unsigned char, N>& magic) {
  if (s.size() < N) return false;
  for (size_t i = 0; i < N; ++i)
    if (static_cast<unsigned char>(s[i]) != magic[i]) return false;
  return true;
}

bool iends_with(std::string_view s, std::string_view suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

}  // namespace

Format sniff(std::string_view head) {
  if (starts_with(head, kGzipMagic)) return Format::Gzip;
  if (starts_with(head, kZstdMagic)) return Format::Zstd;
  return Format::Plain;
}

const char* format_name(Format f) {
  switch (f) {
    case Format::Gzip: return "gzip";
    case Format::Zstd: return "zstd";
    case Format::Plain: break;
  }
  return "plain";
}

std::string_view compression_suffix(std::string_view name) {
  for (std::string_view s : {".gz", ".zst"})
    if (iends_with(name, s)) return name.substr(name.size() - s.size());
  return {};
}

std::string strip_compression_suffix(std::string_view name) {
  return std::string(name.substr(0, name.size() - compression_suffix(name).size()));
}

struct Reader::Impl {
  std::string path;
  uint64_t max_bytes = 0;
  Format format = Format::Plain;
  std::ifstream in;
  std::vector<char> buf = std::vector<char>(kInputChunk);
  size_t pos = 0, len = 0;  // unread input is buf[pos, len)
  bool input_eof = false;
  uint64_t produced = 0;
  bool finished = false;

  z_stream zs{};
  bool zs_open = false;
  bool member_done = false;  // the last inflate ended a gzip member

  ZSTD_DStream* zd = nullptr;
  size_t zstd_hint = 1;  // last ZSTD_decompressStream result; 0 only at a frame's end

  [[noreturn]] void fail(const std::string& what) const { throw SceneError(path + ": " + what); }

  // Refills buf when it is used up; returns the unread byte count (0 at end of file).
  size_t refill() {
    if (pos < len || input_eof) return len - pos;
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    if (in.bad()) fail("cannot read");
    pos = 0;
    len = static_cast<size_t>(in.gcount());
    if (len == 0) input_eof = true;
    return len;
  }

  size_t read_plain(char* out, size_t cap) {
    if (refill() == 0) return 0;
    const size_t n = std::min(cap, len - pos);
    std::copy_n(buf.data() + pos, n, out);
    pos += n;
    return n;
  }

  size_t read_gzip(char* out, size_t cap) {
    zs.next_out = reinterpret_cast<Bytef*>(out);
    zs.avail_out = static_cast<uInt>(std::min(cap, kMaxInflateOut));
    const uInt want = zs.avail_out;
    while (zs.avail_out == want) {
      if (member_done) {
        // gzip allows concatenated members (cat a.gz b.gz); the stream ends only at the
        // end of the file, after a complete member.
        if (refill() == 0) return 0;
        inflateReset(&zs);
        member_done = false;
      }
      const bool at_eof = refill() == 0;
      zs.next_in = reinterpret_cast<Bytef*>(buf.data() + pos);
      zs.avail_in = static_cast<uInt>(len - pos);
      const int ret = inflate(&zs, Z_NO_FLUSH);
      pos = len - zs.avail_in;
      if (ret == Z_STREAM_END) {
        member_done = true;
      } else if (ret == Z_BUF_ERROR && at_eof) {
        // No progress with no input left: inflate flushes pending output first, so this
        // is the file ending inside a member.
        fail("truncated gzip data (the file ends inside the compressed stream)");
      } else if (ret == Z_MEM_ERROR) {
        fail("out of memory while decompressing gzip data");
      } else if (ret != Z_OK && ret != Z_BUF_ERROR) {
        fail(std::string("corrupt gzip data (") + (zs.msg ? zs.msg : "inflate error") + ")");
      }
    }
    return want - zs.avail_out;
  }

  size_t read_zstd(char* out, size_t cap) {
    ZSTD_outBuffer ob{out, cap, 0};
    while (ob.pos == 0) {
      const bool at_eof = refill() == 0;
      if (at_eof && zstd_hint == 0) return 0;  // every frame complete and checked
      ZSTD_inBuffer ib{buf.data() + pos, len - pos, 0};
      const size_t ret = ZSTD_decompressStream(zd, &ob, &ib);
      pos += ib.pos;
      if (ZSTD_isError(ret)) fail(std::string("corrupt zstd data (") + ZSTD_getErrorName(ret) + ")");
      zstd_hint = ret;
      // With no input left, a call that writes nothing has nothing more to flush.
      if (at_eof && ob.pos == 0 && ret != 0)
        fail("truncated zstd data (the file ends inside the compressed stream)");
    }
    return ob.pos;
  }
};

Reader::Reader(const std::string& path, uint64_t max_bytes) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.max_bytes = max_bytes;
  // Only regular files: a directory or device (e.g. an mtllib naming /dev/zero) would
  // fail late or never end.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) m.fail("cannot open");
  m.in.open(path, std::ios::binary);
  if (!m.in) m.fail("cannot open");
  m.refill();
  m.format = sniff(std::string_view(m.buf.data(), m.len));
  const std::string_view suffix = compression_suffix(path);
  if (m.format == Format::Plain && !suffix.empty())
    m.fail("the name ends in " + std::string(suffix) +
           " but the file is not gzip or zstd data (truncated or misnamed; a plain text scene needs a name without " +
           std::string(suffix) + ")");
  if (m.format == Format::Gzip) {
    // 15 + 16: a 32 KiB window and a gzip (not raw zlib) wrapper with its CRC-32.
    if (inflateInit2(&m.zs, 15 + 16) != Z_OK) m.fail("cannot start the gzip decoder");
    m.zs_open = true;
  } else if (m.format == Format::Zstd) {
    m.zd = ZSTD_createDStream();
    if (m.zd == nullptr || ZSTD_isError(ZSTD_initDStream(m.zd))) m.fail("cannot start the zstd decoder");
  }
}

Reader::~Reader() {
  if (impl_->zs_open) inflateEnd(&impl_->zs);
  ZSTD_freeDStream(impl_->zd);  // accepts nullptr
}

Format Reader::format() const { return impl_->format; }
uint64_t Reader::produced() const { return impl_->produced; }

size_t Reader::read(char* out, size_t cap) {
  Impl& m = *impl_;
  if (m.finished || cap == 0) return 0;
  // Ask for at most one byte past the limit: enough to see it crossed, never much more.
  cap = static_cast<size_t>(std::min<uint64_t>(cap, m.max_bytes - m.produced + 1));
  size_t n = 0;
  switch (m.format) {
    case Format::Plain: n = m.read_plain(out, cap); break;
    case Format::Gzip: n = m.read_gzip(out, cap); break;
    case Format::Zstd: n = m.read_zstd(out, cap); break;
  }
  m.produced += n;
  if (m.produced > m.max_bytes)
    m.fail(std::string(m.format == Format::Plain ? "is" : "decompresses to") + " more than " +
           std::to_string(m.max_bytes) + " bytes (the limit for a scene file)");
  if (n == 0) m.finished = true;
  return n;
}

std::string read_all(const std::string& path, uint64_t max_bytes) {
  Reader r(path, max_bytes);
  constexpr size_t kChunk = 1 << 20;  // bytes appended per read
  std::string text;
  for (;;) {
    const size_t old = text.size();
    text.resize(old + kChunk);
    const size_t n = r.read(text.data() + old, kChunk);
    text.resize(old + n);
    if (n == 0) return text;
  }
}

}  // namespace rastsim::scene_stream
