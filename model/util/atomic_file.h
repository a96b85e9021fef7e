// SPDX-License-Identifier: Apache-2.0
// Output files that appear whole or not at all, and temporary folders that go away.
//
// A run writes each output to a temporary name beside its target (same directory, so the
// rename stays on one filesystem): ".STEM.tmp.PID.N.EXT", the target's extension kept
// (writers choose the format by it, and SystemC appends ".vcd" to a VCD's name).
// commit() renames it over the target in one step. A run that ends any other way (a bad
// scene line, a model error, an exception) removes it in the destructor, and SIGINT or
// SIGTERM remove it from the signal handler (interrupt.h): the target is either the whole
// new file or what was there before.
//
// A target that exists but is not a regular file (/dev/null, /dev/stdout, a FIFO) is
// written directly: renaming over it would replace the device. "-" (stdout) is not a
// path: the callers write it to std::cout themselves.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace rastsim {

// A temporary path for a writer that takes a path (libpng, SystemC's VCD, Verilator's FST,
// vcd2fst): write to path(), then commit().
class PendingFile {
 public:
  explicit PendingFile(std::string target);
  ~PendingFile();  // removes the temporary unless committed
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& target() const { return target_; }
  // Where to write: the temporary (the target itself when it is not a regular file).
  const std::string& path() const { return path_; }
  // Renames the temporary over the target; throws naming the target when it cannot (the
  // temporary is then removed).
  void commit();

 private:
  std::string target_, path_;
  bool direct_ = false, committed_ = false;
  int slot_ = -1;  // interrupt.h's registry
};

// An std::ofstream on a PendingFile: stream() while writing, commit() once complete.
class AtomicFile {
 public:
  // Throws "TARGET: cannot open for writing (REASON)".
  explicit AtomicFile(const std::string& target, std::ios::openmode mode = std::ios::binary);
  std::ofstream& stream() { return os_; }
  const std::string& target() const { return file_.target(); }
  // Flushes, checks every write succeeded ("TARGET: write failed"), closes and renames.
  void commit();

 private:
  PendingFile file_;
  std::ofstream os_;
};

// `write(path)` writes the output at a temporary path; then it is committed to `target`.
void write_atomically(const std::string& target, const std::function<void(const std::string& path)>& write);

// Fails before a long run, creating nothing, when `target` cannot be written: a temporary
// beside it is created and removed. "" and "-" pass.
void check_writable(const std::string& target);

// A folder made now and removed with everything in it when this goes out of scope.
class TempDir {
 public:
  // `prefix` + "-PID-N" under the system's temporary directory.
  explicit TempDir(const std::string& prefix);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace rastsim
