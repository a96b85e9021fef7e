// SPDX-License-Identifier: Apache-2.0
// Shared by the libFuzzer targets (docs/fuzzing.md): how a target reports a finding
// (a broken invariant or an exception of the wrong type) and where it writes the files
// a path-taking parser needs.
//
// In a fuzzer a finding aborts: libFuzzer then saves the input as crash-<sha1> and
// prints its path, exactly as for an ASan/UBSan report or a signal. In the gtest that
// replays fuzz/regressions (tb/test_parser_regressions.cpp) it throws Finding, which is
// no std::exception, so no parser's catch can swallow it.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace rastsim::fuzz {

struct Finding {
  std::string what;
};

// Set by the fuzz targets' entry point (fuzz_target.cpp); the gtest leaves it false.
inline bool& abort_on_finding() {
  static bool abort = false;
  return abort;
}

[[noreturn]] inline void finding(const std::string& what) {
  if (!abort_on_finding()) throw Finding{what};
  std::fprintf(stderr, "==FINDING== %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline void check(bool ok, const std::string& what) {
  if (!ok) finding("invariant broken: " + what);
}

// What an input may end in besides success: only the parser's documented error type.
// Any other exception is a finding, named with its type's message.
template <class Documented, class Fn>
void expect_only(const char* documented_name, Fn&& fn) {
  try {
    fn();
  } catch (const Documented&) {
    // the documented outcome of bad input
  } catch (const Finding&) {
    throw;
  } catch (const std::exception& e) {
    finding(std::string("exception other than ") + documented_name + ": " + e.what());
  } catch (...) {
    finding(std::string("non-std exception (not ") + documented_name + ")");
  }
}

// Calls fn(token) for every run of bytes between `separators` in `text`.
template <class Fn>
void for_each_token(std::string_view text, std::string_view separators, Fn&& fn) {
  for (size_t b = text.find_first_not_of(separators); b != std::string_view::npos;
       b = text.find_first_not_of(separators, b)) {
    const size_t e = std::min(text.find_first_of(separators, b), text.size());
    fn(std::string(text.substr(b, e - b)));
    b = e;
  }
}

// A private directory for this process's scratch files (RAM-backed when /dev/shm
// exists), created once and reused: each file is rewritten every execution. Removed at
// a normal exit (a fuzzer that stops on a finding leaves it, with the reproducer's copy).
inline const std::string& scratch_dir() {
  // Never freed: the exit handler below still needs it after static destructors ran.
  static const std::string* dir = [] {
    auto* t = new std::string(std::string(access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") +
                              "/rastsim_fuzz_XXXXXX");
    if (!mkdtemp(t->data())) finding("cannot create a scratch directory");
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(*dir, ec);
    });
    return t;
  }();
  return *dir;
}

// Writes `bytes` to scratch_dir()/name and returns the path.
inline std::string scratch_file(const std::string& name, std::string_view bytes) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) finding("cannot write scratch file " + path);
  return path;
}

}  // namespace rastsim::fuzz
