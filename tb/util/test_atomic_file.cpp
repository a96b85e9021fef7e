// SPDX-License-Identifier: Apache-2.0
// util/atomic_file.h and util/interrupt.h: an output appears whole at commit() or not at
// all (an exception, a signal), a file already there is left as it was, nothing is left
// beside it; a signal during a wait stops the child's whole process group and unwinds.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "util/atomic_file.h"
#include "util/interrupt.h"
#include "util/process.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

// A fresh empty folder per test.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rastsim-atomic-test-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string read(const std::string& p) {
    std::ifstream is(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  }
  static void write(const std::string& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

  fs::path dir_;
};

TEST_F(AtomicFileTest, AppearsOnlyAtCommitBesideItsTarget) {
  AtomicFile f(path("out.json"));
  f.stream() << "{\"a\": 1}\n";
  // Before commit: one hidden temporary in the same folder, with the target's extension.
  const auto before = listing();
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].rfind(".out.tmp.", 0), 0u) << before[0];
  EXPECT_EQ(fs::path(before[0]).extension(), ".json");
  f.commit();
  EXPECT_EQ(listing(), std::vector<std::string>{"out.json"});
  EXPECT_EQ(read(path("out.json")), "{\"a\": 1}\n");
}

TEST_F(AtomicFileTest, AnUncommittedFileLeavesNothing) {
  {
    AtomicFile f(path("frags.txt"));
    for (int k = 0; k < 100000; ++k) f.stream() << k << " 1 2 3\n";
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFileTest, AFailedRunLeavesAnOldFileAsItWas) {
  write(path("out.png"), "the previous image");
  EXPECT_THROW(write_atomically(path("out.png"),
                                [](const std::string& tmp) {
                                  write(tmp, "half an image");
                                  throw std::runtime_error("model error");
                                }),
               std::runtime_error);
  EXPECT_EQ(read(path("out.png")), "the previous image");
  EXPECT_EQ(listing(), std::vector<std::string>{"out.png"});
  // A run that succeeds replaces it.
  write_atomically(path("out.png"), [](const std::string& tmp) { write(tmp, "the new image"); });
  EXPECT_EQ(read(path("out.png")), "the new image");
  EXPECT_EQ(listing(), std::vector<std::string>{"out.png"});
}

TEST_F(AtomicFileTest, TwoOutputsOfOneTargetNameGetTwoTemporaries) {
  PendingFile a(path("x.vcd")), b(path("x.vcd"));
  EXPECT_NE(a.path(), b.path());
  EXPECT_EQ(fs::path(a.path()).parent_path(), dir_);
}

TEST_F(AtomicFileTest, ADeviceIsWrittenInPlaceNeverReplaced) {
  AtomicFile f("/dev/null");
  f.stream() << "discarded\n";
  f.commit();
  struct stat st {};
  ASSERT_EQ(stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST_F(AtomicFileTest, CheckWritableCreatesNothing) {
  check_writable(path("stats.json"));
  EXPECT_TRUE(listing().empty());
  check_writable("-");
  check_writable("");
  try {
    check_writable(path("no/such/dir/stats.json"));
    FAIL() << "a missing folder passed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/dir/stats.json: cannot open for writing"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFileTest, ATempDirGoesWithEverythingInIt) {
  fs::path p;
  {
    const TempDir d("rastsim-atomic-test-dir");
    p = d.path();
    write(d.file("a"), "x");
    fs::create_directories(p / "sub");
    write((p / "sub" / "b").string(), "y");
    EXPECT_TRUE(fs::is_directory(p));
  }
  EXPECT_FALSE(fs::exists(p));
}

// The rest fork: the handler is installed in the child only, so the test binary keeps
// the default actions. The child reports through its exit status.

// SIGINT while an output is half written (no InterruptScope): the process ends by the
// signal, as without the handler, and the temporary is gone.
TEST_F(AtomicFileTest, SigintRemovesTheTemporaryAndEndsTheProcess) {
  write(path("old.ppm"), "kept");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    install_interrupt_handler();
    AtomicFile a(path("new.ppm")), b(path("old.ppm"));
    a.stream() << "partial" << std::flush;
    b.stream() << "partial" << std::flush;
    const char c = 1;
    if (::write(ready[1], &c, 1) != 1) _exit(3);
    for (;;) pause();
  }
  close(ready[1]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  close(ready[0]);
  EXPECT_EQ(listing().size(), 3u);  // old.ppm and the two temporaries
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_EQ(listing(), std::vector<std::string>{"old.ppm"});
  EXPECT_EQ(read(path("old.ppm")), "kept");
}

// Whether process `pid` is gone (or a zombie nobody has reaped yet: it runs no more).
bool gone(pid_t pid) {
  std::ifstream is("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(is, stat)) return true;
  const size_t paren = stat.rfind(')');
  return paren != std::string::npos && stat.size() > paren + 2 && stat[paren + 2] == 'Z';
}

// SIGTERM while waiting for a child: its whole group (a grandchild as a compiler under
// `cmake --build`) is stopped, the wait throws Interrupted, destructors run (the TempDir
// goes), and the handler does not end the process.
TEST_F(AtomicFileTest, ASignalDuringAWaitStopsTheChildsGroupAndUnwinds) {
  const std::string grandchild_pid = path("grandchild.pid"), tmp_name = path("tempdir.name");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    install_interrupt_handler();
    int code = 1;
    try {
      const TempDir d("rastsim-atomic-test-wait");
      write(tmp_name, d.path().string());
      // sh starts a grandchild in its (the child's) process group, then both sleep.
      run_process({"sh", "-c", "sleep 60 & echo $! > '" + grandchild_pid + "'; wait"});
      code = 2;  // the wait returned without an exception
    } catch (const Interrupted& e) {
      code = e.signal() == SIGTERM && std::string(e.what()) == "interrupted by SIGTERM" ? 0 : 3;
    } catch (...) {
      code = 4;
    }
    _exit(code);
  }
  for (int k = 0; k < 500 && !fs::exists(grandchild_pid); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the pid written in full
  const pid_t sleeper = std::stoi(read(grandchild_pid));
  EXPECT_FALSE(gone(sleeper));
  kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the handler ended the process: status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 0);
  for (int k = 0; k < 200 && !gone(sleeper); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(gone(sleeper)) << "the grandchild " << sleeper << " runs on";
  EXPECT_FALSE(fs::exists(read(tmp_name)));
}

TEST(ShellCommand, QuotesOnlyTheWordsThatNeedIt) {
  EXPECT_EQ(shell_command({"./rastsim", "sweep", "--set", "raster.tile_size=8,16", "--out", "a b.csv", "it's", ""}),
            "./rastsim sweep --set raster.tile_size=8,16 --out 'a b.csv' 'it'\\''s' ''");
}

}  // namespace
}  // namespace rastsim
