// SPDX-License-Identifier: Apache-2.0
// Compressed scenes (model/scene/scene_stream.*): the shipped traces and the test cube,
// compressed here with zlib's deflate and libzstd's compressor (independently of the
// reader), render to the same framebuffer CRC as the plain files; errors in compressed
// files name their line; truncated, corrupt and oversized streams are clear errors.
#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "scene_test.h"
#include "ref/pipeline.h"
#include "ref/scene.h"
#include "scene/scene_io.h"
#include "scene/scene_stream.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;
using scene_test::SceneFails;
namespace ss = scene_stream;

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << p;
}

// gzip (RFC 1952) through deflate with a gzip wrapper (windowBits 15 + 16).
std::string gzip(const std::string& text) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, text.size()), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  zs.avail_in = static_cast<uInt>(text.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

// One zstd frame with a content checksum, as the zstd command-line tool writes by default.
std::string zstd(const std::string& text) {
  ZSTD_CCtx* cc = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cc, ZSTD_c_checksumFlag, 1);
  std::string out(ZSTD_compressBound(text.size()), '\0');
  const size_t n = ZSTD_compress2(cc, out.data(), out.size(), text.data(), text.size());
  ZSTD_freeCCtx(cc);
  EXPECT_FALSE(ZSTD_isError(n));
  out.resize(n);
  return out;
}

using Compressor = std::string (*)(const std::string&);
struct Codec {
  const char* suffix;
  Compressor compress;
};
const Codec kCodecs[] = {{".gz", gzip}, {".zst", zstd}};

// A fresh directory per test, removed afterwards.
class CompressedScene : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("rastsim_ztest_" + std::to_string(getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string put(const std::string& name, const std::string& bytes) {
    write_file(dir_ / name, bytes);
    return (dir_ / name).string();
  }
  fs::path dir_;
};

const ObjPlacement& placement() {
  static const ObjPlacement p = obj_placement_from_config(Config{});
  return p;
}

// Loads and renders `path`; the scene's CRC and counts must equal the reference's.
void expect_same_render(const std::string& path, const RenderStats& want, size_t commands) {
  SCOPED_TRACE(path);
  Scene s;
  ASSERT_NO_THROW(s = load_scene(path, placement()));
  EXPECT_EQ(s.commands.size(), commands);
  const RenderStats got = scene_test::render_default(s);
  EXPECT_EQ(got.framebuffer_crc32, want.framebuffer_crc32);
  EXPECT_EQ(got.triangles_in, want.triangles_in);
  EXPECT_EQ(got.fragments_passed, want.fragments_passed);
}

TEST_F(CompressedScene, ShippedTracesRenderLikeThePlainFiles) {
  std::vector<fs::path> traces;
  for (const char* sub : {"traces", "traces/2d", "traces/3d"})
    for (const auto& e : fs::directory_iterator(fs::path(RASTSIM_SOURCE_DIR) / sub))
      if (e.path().extension() == ".trace") traces.push_back(e.path());
  ASSERT_GE(traces.size(), 5u);
  for (const fs::path& t : traces) {
    SCOPED_TRACE(t.string());
    const Scene plain = load_scene(t.string(), placement());
    const RenderStats want = scene_test::render_default(plain);
    const std::string text = file_text(t);
    const std::string stem = t.filename().string();
    for (const Codec& c : kCodecs) {
      expect_same_render(put(stem + c.suffix, c.compress(text)), want, plain.commands.size());
      // Two members / frames split mid-line (cat a.gz b.gz) read as one text.
      const size_t half = text.size() / 2 + 1;
      expect_same_render(put("two_" + stem + c.suffix, c.compress(text.substr(0, half)) + c.compress(text.substr(half))),
                         want, plain.commands.size());
    }
  }
}

// cube.obj with its MTL: .obj.gz / .obj.zst choose the OBJ parser by the name without
// the suffix, and an mtllib naming a compressed .mtl reads it the same way.
TEST_F(CompressedScene, ObjAndItsMaterialLibraryRenderLikeThePlainFiles) {
  const fs::path data = RASTSIM_TEST_DATA;
  const std::string obj = file_text(data / "cube.obj"), mtl = file_text(data / "cube.mtl");
  const Scene plain = load_obj((data / "cube.obj").string(), placement());
  const RenderStats want = scene_test::render_default(plain);
  ASSERT_NE(obj.find("mtllib cube.mtl\n"), std::string::npos);
  put("blue.png", file_text(data / "blue.png"));  // cube.mtl's map_Kd must exist
  for (const Codec& c : kCodecs) {
    put("cube.mtl", mtl);
    expect_same_render(put(std::string("cube.obj") + c.suffix, c.compress(obj)), want, plain.commands.size());
    std::string obj2 = obj;
    obj2.replace(obj2.find("mtllib cube.mtl\n"), 16, std::string("mtllib m.mtl") + c.suffix + "\n");
    put(std::string("m.mtl") + c.suffix, c.compress(mtl));
    expect_same_render(put(std::string("CUBE2.OBJ") + c.suffix, c.compress(obj2)), want, plain.commands.size());
  }
}

// A UTF-8 byte-order mark after decompression is read past by the whole-file and the
// streamed reader, in traces and OBJ meshes alike.
TEST_F(CompressedScene, ByteOrderMarkAfterDecompression) {
  const std::string bom = "\xEF\xBB\xBF", trace = "clear 1 2 3\ntri 0 0 8 0 0 8\n";
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const RenderStats want_trace = scene_test::render_default(parse_trace(trace, "t.trace"));
  const RenderStats want_obj = scene_test::render_default(parse_obj(obj, "t.obj", placement(), "."));
  for (const Codec& c : kCodecs) {
    const std::string t = put("bom.trace" + std::string(c.suffix), c.compress(bom + trace));
    expect_same_render(t, want_trace, 2);
    size_t streamed = 0;
    stream_scene(t, placement(), 1, [&](std::vector<Command>& b) { streamed += b.size(); });
    EXPECT_EQ(streamed, 2u);
    expect_same_render(put("bom.obj" + std::string(c.suffix), c.compress(bom + obj)), want_obj, 3);
  }
}

// Any chunk size gives the same bytes: the reader's state carries across calls.
TEST_F(CompressedScene, ChunkedReadsReassembleTheText) {
  const std::string text = file_text(fs::path(RASTSIM_SOURCE_DIR) / "traces/torus.trace");
  const std::string paths[] = {put("t.trace", text), put("t.trace.gz", gzip(text)), put("t.trace.zst", zstd(text))};
  const ss::Format formats[] = {ss::Format::Plain, ss::Format::Gzip, ss::Format::Zstd};
  for (int i = 0; i < 3; ++i) {
    for (size_t cap : {size_t{1}, size_t{7}, size_t{4096}, size_t{1} << 20}) {
      SCOPED_TRACE(paths[i] + " cap " + std::to_string(cap));
      ss::Reader r(paths[i]);
      EXPECT_EQ(r.format(), formats[i]);
      std::string got, chunk(cap, '\0');
      for (size_t n; (n = r.read(chunk.data(), cap)) > 0;) {
        ASSERT_LE(n, cap);
        got.append(chunk.data(), n);
      }
      EXPECT_EQ(got, text);
      EXPECT_EQ(r.produced(), text.size());
      EXPECT_EQ(r.read(chunk.data(), cap), 0u);  // stays at the end
    }
  }
}

// A parse error on line N of a compressed file names that file (as given) and line N.
TEST_F(CompressedScene, ErrorsNameTheLineOfTheCompressedFile) {
  for (const Codec& c : kCodecs) {
    for (int bad : {1, 2, 7}) {
      std::string text;
      for (int l = 1; l < bad; ++l) text += l == 1 ? "viewport 64 64\n" : "# comment\n";
      text += "tri 0 0 10 0 0 zz\nclear 0 0 0\n";
      const std::string p = put("bad.trace" + std::string(c.suffix), c.compress(text));
      EXPECT_TRUE(SceneFails([&] { load_scene(p, placement()); }, p + ":" + std::to_string(bad) + ":", ""));
    }
    const std::string obj = put(std::string("bad.obj") + c.suffix, c.compress("v 0 0 0\nv 1 0 0\nf 1 2 9\n"));
    EXPECT_TRUE(SceneFails([&] { load_scene(obj, placement()); }, obj + ":3:", "index"));
    const std::string mtl = put(std::string("bad.mtl") + c.suffix, c.compress("newmtl a\nKd 1 x 1\n"));
    const std::string obj2 = put(std::string("m.obj") + c.suffix,
                                 c.compress(std::string("mtllib bad.mtl") + c.suffix + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_TRUE(SceneFails([&] { load_scene(obj2, placement()); }, mtl + ":2:", "Kd"));
  }
}

// Every prefix of a compressed file is an error naming the file: none reads as a
// shorter scene, none crashes.
TEST_F(CompressedScene, EveryTruncationIsAnError) {
  const std::string text = file_text(fs::path(RASTSIM_SOURCE_DIR) / "traces/primitives.trace");
  for (const Codec& c : kCodecs) {
    const std::string z = c.compress(text);
    const std::string p = (dir_ / (std::string("cut.trace") + c.suffix)).string();
    const size_t magic = std::string(c.suffix) == ".gz" ? 2 : 4;  // bytes
    for (size_t n = 0; n < z.size(); ++n) {
      SCOPED_TRACE(p + " cut to " + std::to_string(n) + " of " + std::to_string(z.size()) + " bytes");
      write_file(p, z.substr(0, n));
      EXPECT_TRUE(SceneFails([&] { load_scene(p, placement()); }, p + ":", n < magic ? "not gzip or zstd" : "truncated"));
    }
  }
}

// Flipping any one byte either gives an error naming the file or the exact original
// text (a header field neither format checks, e.g. gzip's mtime); never different text.
// gzip's CRC-32 and the zstd frame checksum make corruption of the data visible.
TEST_F(CompressedScene, CorruptionIsAnErrorNeverADifferentScene) {
  const std::string text = file_text(fs::path(RASTSIM_SOURCE_DIR) / "traces/state.trace");
  for (const Codec& c : kCodecs) {
    const std::string z = c.compress(text);
    const std::string p = (dir_ / (std::string("bad.trace") + c.suffix)).string();
    int errors = 0;
    for (size_t i = 0; i < z.size(); ++i) {
      SCOPED_TRACE(p + " byte " + std::to_string(i));
      std::string bad = z;
      bad[i] = static_cast<char>(bad[i] ^ 0x5a);
      write_file(p, bad);
      try {
        EXPECT_EQ(ss::read_all(p), text);
      } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(p + ": ", 0), 0u) << e.what();
        ++errors;
      }
    }
    EXPECT_GT(errors, static_cast<int>(z.size()) * 3 / 4) << c.suffix;
  }
  // Trailing garbage after a complete gzip member is not ignored.
  const std::string p = put("tail.trace.gz", gzip(text) + "garbage");
  EXPECT_TRUE(SceneFails([&] { ss::read_all(p); }, p + ":", "corrupt gzip data"));
}

// A stream that inflates past the limit stops there (bounded memory) with an error. The
// default limit is 4 GiB; a small one here keeps the test fast. The plain file limit is
// the same rule.
TEST_F(CompressedScene, DecompressionBombIsStoppedAtTheLimit) {
  EXPECT_EQ(ss::kMaxSceneBytes, uint64_t{4} << 30);
  const std::string blank(64 << 20, '\n');  // 64 MiB of empty lines, a valid trace
  constexpr uint64_t kLimit = 1 << 20;
  for (const Codec& c : kCodecs) {
    const std::string z = c.compress(blank);
    EXPECT_LT(z.size(), 100u << 10) << c.suffix;  // a real bomb: > 600x
    const std::string p = put(std::string("bomb.trace") + c.suffix, z);
    EXPECT_TRUE(SceneFails([&] { ss::read_all(p, kLimit); }, p + ":", "decompresses to more than 1048576 bytes"));
    // Exactly at the limit is fine; one byte over is not.
    const std::string q = put(std::string("edge.trace") + c.suffix, c.compress(blank.substr(0, kLimit)));
    EXPECT_EQ(ss::read_all(q, kLimit).size(), kLimit);
    EXPECT_TRUE(SceneFails([&] { ss::read_all(q, kLimit - 1); }, q + ":", "more than 1048575 bytes"));
  }
  const std::string plain = put("big.trace", blank.substr(0, kLimit + 1));
  EXPECT_TRUE(SceneFails([&] { ss::read_all(plain, kLimit); }, plain + ":", "is more than 1048576 bytes"));
}

// Documented rule: the magic bytes choose the decoder; a name ending in .gz / .zst must
// hold compressed data (so a file truncated to nothing is not an empty scene), and a
// compressed file with a plain name is still decompressed.
TEST_F(CompressedScene, TheContentDecidesAndACompressedNameMustHoldCompressedData) {
  const std::string text = "viewport 8 8\nclear 1 2 3\ntri 0 0 4 0 0 4\n";
  for (const char* name : {"plain.trace.gz", "plain.trace.zst", "PLAIN.TRACE.GZ", "empty.trace.gz"}) {
    const std::string p = put(name, std::string(name).starts_with("empty") ? "" : text);
    EXPECT_TRUE(SceneFails([&] { load_scene(p, placement()); }, p + ":", "is not gzip or zstd data")) << name;
  }
  const size_t want = parse_trace(text, "x").commands.size();
  EXPECT_EQ(load_scene(put("gz_inside.trace", gzip(text)), placement()).commands.size(), want);
  EXPECT_EQ(load_scene(put("zst_named.trace.gz", zstd(text)), placement()).commands.size(), want);
  EXPECT_EQ(ss::strip_compression_suffix("a/b.OBJ.GZ"), "a/b.OBJ");
  EXPECT_EQ(ss::strip_compression_suffix("b.trace.zst"), "b.trace");
  EXPECT_EQ(ss::strip_compression_suffix("b.tgz"), "b.tgz");
  EXPECT_EQ(ss::sniff("\x1f\x8b"), ss::Format::Gzip);
  EXPECT_EQ(ss::sniff("\x28\xb5\x2f"), ss::Format::Plain);  // too short for the zstd magic
}

}  // namespace
}  // namespace rastsim
