// SPDX-License-Identifier: Apache-2.0
#include "util/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "util/interrupt.h"

namespace fs = std::filesystem;

namespace rastsim {

namespace {

std::atomic<unsigned> serial{0};  // several temporaries of one target in one process

// ".STEM.tmp.PID.N.EXT" in the target's directory.
std::string temp_name(const std::string& target) {
  const fs::path t(target);
  const std::string name = "." + t.stem().string() + ".tmp." + std::to_string(getpid()) + "." +
                           std::to_string(serial++) + t.extension().string();
  return (t.parent_path() / name).string();
}

// An existing target that is not a regular file (a device, a FIFO) is written in place.
bool write_in_place(const std::string& target) {
  struct stat st {};
  return stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

}  // namespace

PendingFile::PendingFile(std::string target) : target_(std::move(target)) {
  direct_ = write_in_place(target_);
  path_ = direct_ ? target_ : temp_name(target_);
  if (!direct_) slot_ = register_temp_file(path_.c_str());
}

PendingFile::~PendingFile() {
  if (direct_ || committed_) return;
  std::remove(path_.c_str());
  unregister_temp_file(slot_);
}

void PendingFile::commit() {
  if (direct_ || committed_) return;
  if (std::rename(path_.c_str(), target_.c_str()) != 0)
    throw std::runtime_error(target_ + ": cannot write (rename of " + path_ + ": " + std::strerror(errno) + ")");
  committed_ = true;
  unregister_temp_file(slot_);  // after the rename: a signal meanwhile finds no file to unlink
}

AtomicFile::AtomicFile(const std::string& target, std::ios::openmode mode)
    : file_(target), os_(file_.path(), mode | std::ios::out | std::ios::trunc) {
  if (!os_) throw std::runtime_error(target + ": cannot open for writing (" + std::strerror(errno) + ")");
}

void AtomicFile::commit() {
  os_.close();
  if (!os_) throw std::runtime_error(target() + ": write failed");
  file_.commit();
}

void write_atomically(const std::string& target, const std::function<void(const std::string& path)>& write) {
  PendingFile f(target);
  write(f.path());
  f.commit();
}

void check_writable(const std::string& target) {
  if (target.empty() || target == "-") return;
  const PendingFile f(target);
  const int fd = open(f.path().c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (f.path() == target ? 0 : O_EXCL), 0644);
  if (fd < 0) throw std::runtime_error(target + ": cannot open for writing (" + std::strerror(errno) + ")");
  close(fd);
}

TempDir::TempDir(const std::string& prefix)
    : path_(fs::temp_directory_path() / (prefix + "-" + std::to_string(getpid()) + "-" + std::to_string(serial++))) {
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

}  // namespace rastsim
