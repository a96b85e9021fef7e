// SPDX-License-Identifier: Apache-2.0
// Mutation fuzz of both scene parsers: thousands of seeded random byte and token edits
// (delete, duplicate, flip, insert garbage, truncate) of valid traces and OBJ text.
// The only allowed outcomes are a Scene or a SceneError; any other exception fails the
// test and a crash kills it. Some parsed scenes are also rendered, where again only
// SceneError may escape. Set RASTSIM_FUZZ_SEED to replay a run; the seed is printed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>

#include "scene_test.h"
#include "ref/pipeline.h"
#include "ref/scene.h"
#include "scene/scene_io.h"

namespace rastsim {
namespace {

const std::string kData = RASTSIM_TEST_DATA;

uint64_t fuzz_seed() {
  if (const char* env = std::getenv("RASTSIM_FUZZ_SEED")) return std::strtoull(env, nullptr, 0);
  return 0x5ce7e5eedULL;  // fixed by default so CI runs are reproducible
}

// Tokens that sit on the parsers' edges: separators, limits, keywords, bad numbers.
const std::string kGarbage[] = {
    " ", "\n", "\r\n", "\t", "#", "/", "//", "-", "+", ".", "0", "-0", "1e999", "-1e-999", "nan", "inf",
    "-1", "256", "1.0000001", "99999999999999999999999", "-9223372036854775808", "0.0000000000000000000000000000000000001",
    std::string(1, '\0'), "\xff\xfe", "end", "strip", "fan", "v", "tri", "f", "usemtl red", "usemtl blue",
    "mtllib cube.mtl", "mtllib bad_kd.mtl", "mtllib .", "mtllib /", "vt 0", "vn 0 0 1", "scissor off",
    "viewport 16384 16384", "f -1 -2 -3", "f 1/1/1 2//2 3", std::string(300, '9'), std::string(5000, 'x')};

std::string mutate(std::string s, std::mt19937_64& rng) {
  auto pick = [&](size_t n) { return n == 0 ? size_t{0} : size_t(rng() % n); };
  const int edits = 1 + int(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const size_t at = pick(s.size() + 1);
    switch (rng() % 7) {
      case 0:  // delete a short range
        if (at < s.size()) s.erase(at, 1 + pick(8));
        break;
      case 1:  // duplicate a range somewhere else
        if (at < s.size()) s.insert(pick(s.size() + 1), s.substr(at, 1 + pick(64)));
        break;
      case 2:  // flip one byte, to anything or to a character the grammar cares about
        if (at < s.size()) {
          static const std::string kSyntax = "0123456789-+./#e \n\t";
          s[at] = rng() % 2 ? char(rng() & 0xff) : kSyntax[pick(kSyntax.size())];
        }
        break;
      case 3:  // insert a garbage token
        s.insert(at, " " + kGarbage[pick(std::size(kGarbage))] + " ");
        break;
      case 4:  // truncate
        s.resize(at);
        break;
      case 5: {  // replace the whitespace-delimited token around `at`
        const size_t b = s.find_last_of(" \n", at == 0 ? 0 : at - 1);
        const size_t from = b == std::string::npos ? 0 : b + 1;
        const size_t to = std::min(s.find_first_of(" \n", from), s.size());
        s.replace(from, to - from, kGarbage[pick(std::size(kGarbage))]);
        break;
      }
      default: {  // duplicate or drop a whole line
        const size_t b = s.rfind('\n', at == 0 ? 0 : at - 1);
        const size_t from = b == std::string::npos ? 0 : b + 1;
        const size_t to = std::min(s.find('\n', from), s.size());
        if (rng() % 2) s.insert(from, s.substr(from, to - from) + "\n");
        else s.erase(from, to - from);
      }
    }
  }
  return s;
}

// A printable copy of a mutated input for the failure message.
std::string escaped(const std::string& s) {
  std::string out;
  for (unsigned char c : s.substr(0, 2000)) {
    if (c == '\n' || (c >= 0x20 && c < 0x7f)) out += char(c);
    else out += "\\x" + std::string(1, "0123456789abcdef"[c >> 4]) + "0123456789abcdef"[c & 15];
  }
  return out;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct FuzzCounts {
  int parsed = 0, rejected = 0;        // parse outcomes
  int rendered = 0, render_errors = 0;  // of the parsed scenes that were rendered
};

// Runs `iterations` mutants of the corpus through `parse`; reports anything but a
// Scene or a SceneError. Every 8th parsed scene is also rendered.
void fuzz(const std::vector<std::string>& corpus, int iterations, std::mt19937_64& rng, uint64_t seed,
          const std::function<Scene(const std::string&, std::mt19937_64&)>& parse, FuzzCounts& n) {
  for (int i = 0; i < iterations; ++i) {
    const std::string text = mutate(corpus[rng() % corpus.size()], rng);
    const char* stage = "parse";
    try {
      const Scene s = parse(text, rng);
      ++n.parsed;
      if (n.parsed % 8 == 0) {
        stage = "render";
        ++n.rendered;
        scene_test::render_default(s);
      }
    } catch (const SceneError&) {
      ++(stage[0] == 'p' ? n.rejected : n.render_errors);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "seed " << seed << " iteration " << i << ": " << stage << " threw a non-SceneError: "
                    << e.what() << "\n--- input ---\n" << escaped(text);
    }
  }
}

TEST(SceneFuzz, MutatedTracesAndObjsGiveSceneOrSceneError) {
  const uint64_t seed = fuzz_seed();
  std::cout << "[ SEED     ] RASTSIM_FUZZ_SEED=" << seed << std::endl;
  RecordProperty("seed", std::to_string(seed));
  std::mt19937_64 rng(seed);
  const auto t0 = std::chrono::steady_clock::now();

  std::vector<std::string> traces = {
      "viewport 128 128\nclear 1 2 3\ncleardepth 1\nscissor 0 0 64 64\nscissor off\n"
      "color 10 20 30\ndepth 0.5\ntri 1 2 30 4 5 60\n"
      "tri 1 2 0 255 0 0 30 4 0.5 0 255 0 5 60 1 0 0 255\n"
      "strip\nv 0 0\nv 0 10 0.5 1 2 3\nv 10 0\nv 10 10\nend\n"
      "fan # c\nv 5 5\nv 0 0\nv 10.25 0\nv 10 10\nend\n"};
  for (const char* t : {"primitives", "fill_rule", "state", "3d/clip_cube"})
    traces.push_back(file_text(std::string(RASTSIM_SOURCE_DIR) + "/traces/" + t + ".trace"));
  traces.push_back(file_text(std::string(RASTSIM_SOURCE_DIR) + "/fuzz/corpus/trace/clip.trace"));
  const std::vector<std::string> objs = {
      file_text(kData + "/cube.obj"), file_text(std::string(RASTSIM_SOURCE_DIR) + "/fuzz/corpus/obj/perspective.obj"),
      "mtllib cube.mtl\nv 0 0 0\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nv 1 1 0 1\nvt 0 0\nvn 0 0 1\n"
      "usemtl blue\nf 1/1/1 2/1/1 3/1/1\nf -1//-1 -2//1 -3//1\ng x\ns 1\nf 1 2 4 3\n"};
  for (const auto& t : traces) ASSERT_NO_THROW(parse_trace(t, "seed.trace"));
  ObjPlacement perspective = obj_placement_from_config(Config{});  // which draws every seed's l and p
  perspective.camera = ObjCamera::Perspective;
  for (const auto& t : objs) ASSERT_NO_THROW(parse_obj(t, "seed.obj", perspective, kData));

  FuzzCounts tn, on;
  fuzz(traces, 8000, rng, seed, [](const std::string& t, std::mt19937_64&) { return parse_trace(t, "fuzz.trace"); },
       tn);
  fuzz(objs, 5000, rng, seed,
       [](const std::string& t, std::mt19937_64& r) {
         ObjPlacement p = obj_placement_from_config(Config{});  // placements vary too, within the config's ranges
         p.yaw_deg = double(r() % 721) - 360;
         p.pitch_deg = double(r() % 181) - 90;
         p.fill = 0.01 + double(r() % 400) / 100;
         if (r() % 2) {  // the perspective camera, sometimes with its eye inside the mesh
           p.camera = ObjCamera::Perspective;
           p.distance = double(r() % 400) / 100;
         }
         return parse_obj(t, "fuzz.obj", p, kData);
       },
       on);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& [what, n] : {std::pair{"traces", tn}, std::pair{"objs", on}})
    std::cout << "[ FUZZ     ] " << what << ": " << n.parsed << " parsed, " << n.rejected << " rejected; "
              << n.rendered << " rendered, " << n.render_errors << " of them with a SceneError" << std::endl;
  std::cout << "[ FUZZ     ] " << secs << " s" << std::endl;
  // Both outcomes must actually occur, or the mutations are too weak or too strong.
  EXPECT_GT(tn.parsed, 100);
  EXPECT_GT(tn.rejected, 1000);
  EXPECT_GT(on.parsed, 100);
  EXPECT_GT(on.rejected, 500);
}

// Valid scenes end to end: the parsed example traces and the cube render without error.
TEST(SceneFuzz, ValidScenesRenderEndToEnd) {
  for (const char* t : {"primitives", "fill_rule", "state"}) {
    const Scene s = load_trace(std::string(RASTSIM_SOURCE_DIR) + "/traces/" + t + ".trace");
    EXPECT_NO_THROW(scene_test::render_default(s)) << t;
  }
  EXPECT_NO_THROW(scene_test::render_default(load_obj(kData + "/cube.obj", obj_placement_from_config(Config{}))));
}

}  // namespace
}  // namespace rastsim
