// SPDX-License-Identifier: Apache-2.0
// util/process.h: programs run from an argv vector with every kind of stream, their exit
// statuses and signals, a program that is not there, this binary run again, a function
// in a forked child, and the one shell quoting (checked by a real /bin/sh reading it back).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/process.h"

namespace rastsim {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("rastsim-util-test-" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream is(p);
  return std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
}

ProcessOptions capture_both() {
  ProcessOptions o;
  o.out = o.err = Sink::Capture;
  return o;
}

TEST(Process, CapturesStdoutAndStderrApartWithTheExitStatus) {
  const ProcessResult r = run_process({"sh", "-c", "printf out; printf err >&2; exit 3"}, capture_both());
  EXPECT_EQ(r.out, "out");
  EXPECT_EQ(r.err, "err");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(exit_code(r.status), 3);
  EXPECT_EQ(status_text(r.status), "exit status 3");
  EXPECT_TRUE(run_process({"true"}).ok());
}

TEST(Process, ArgumentsReachTheProgramAsTheyAre) {
  const std::vector<std::string> args = {"two words", "it's", "$HOME", "`x`;rm", "", "*"};
  std::vector<std::string> argv = {"sh", "-c", "for a; do printf '[%s]' \"$a\"; done", "sh"};
  argv.insert(argv.end(), args.begin(), args.end());
  ProcessOptions o;
  o.out = Sink::Capture;
  EXPECT_EQ(run_process(argv, o).out, "[two words][it's][$HOME][`x`;rm][][*]");
}

TEST(Process, FeedsStdinWhileReadingStdout) {
  // 4 MB through cat both ways: more than a pipe holds, so feeding and reading must
  // interleave.
  std::string input;
  for (int i = 0; input.size() < (4u << 20); ++i) input += std::to_string(i) + "\n";
  ProcessOptions o = capture_both();
  o.feed_input = true;
  o.input = input;
  const ProcessResult r = run_process({"cat"}, o);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.out.size(), input.size());
  EXPECT_TRUE(r.out == input);
}

TEST(Process, AChildThatStopsReadingStdinIsNoSigpipe) {
  ProcessOptions o;
  o.feed_input = true;
  o.input = std::string(8u << 20, 'x');
  EXPECT_TRUE(run_process({"true"}, o).ok());  // this process is still alive to check it
}

TEST(Process, LinesMergeStderrIntoStdout) {
  std::vector<std::string> lines;
  ProcessOptions o;
  o.out = Sink::Lines;
  o.err = Sink::Stdout;
  o.on_line = [&](const std::string& l) { lines.push_back(l); };
  EXPECT_TRUE(run_process({"sh", "-c", "echo a; echo b >&2; printf 'c\\n\\nlast'"}, o).ok());
  EXPECT_EQ(lines, (std::vector<std::string>{"a", "b", "c", "", "last"}));
}

TEST(Process, RedirectsToFilesInAWorkingDirectory) {
  const fs::path d = temp_dir();
  ProcessOptions o;
  o.cwd = d.string();
  o.out = Sink::File;
  o.out_path = (d / "out.txt").string();
  o.err = Sink::File;
  o.err_path = (d / "err.txt").string();
  o.stdin_null = true;
  EXPECT_TRUE(run_process({"sh", "-c", "pwd; cat; echo oops >&2"}, o).ok());
  EXPECT_EQ(read(d / "out.txt"), fs::canonical(d).string() + "\n");
  EXPECT_EQ(read(d / "err.txt"), "oops\n");
  EXPECT_EQ(last_line((d / "err.txt").string()), "oops");
  EXPECT_EQ(last_line((d / "none.txt").string()), "(no message)");
  o.out_path = (d / "no-such-dir" / "out.txt").string();
  EXPECT_THROW(run_process({"true"}, o), std::runtime_error);
  fs::remove_all(d);
}

TEST(Process, AMissingProgramExits127AndSaysSo) {
  const ProcessResult r = run_process({"rastsim-no-such-program"}, capture_both());
  EXPECT_EQ(exit_code(r.status), 127);
  EXPECT_EQ(r.err, "cannot run rastsim-no-such-program: No such file or directory\n");
  EXPECT_EQ(find_program("rastsim-no-such-program"), "");
  const std::string sh = find_program("sh");
  ASSERT_FALSE(sh.empty());
  EXPECT_EQ(fs::path(sh).filename(), "sh");
  EXPECT_EQ(find_program(sh), sh);
  EXPECT_EQ(find_program("/"), "");  // a directory is no program
  EXPECT_THROW(run_process({}), std::runtime_error);
}

TEST(Process, AKilledChildReportsItsSignal) {
  const ProcessResult r = run_process({"sh", "-c", "kill -KILL $$"});
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(exit_code(r.status), 128 + SIGKILL);
  EXPECT_EQ(status_text(r.status), "signal 9 (Killed)");
}

TEST(Process, StartedChildrenAreWaitedFor) {
  const pid_t a = start_process({"sh", "-c", "exit 5"});
  EXPECT_EQ(exit_code(wait_process(a)), 5);
  const pid_t b = start_process({"sh", "-c", "exit 6"});
  const auto [pid, status] = wait_any_process();
  EXPECT_EQ(pid, b);
  EXPECT_EQ(exit_code(status), 6);
  EXPECT_THROW(wait_any_process(), std::runtime_error);  // none left
  ProcessOptions o;
  o.out = Sink::Capture;
  EXPECT_THROW(start_process({"true"}, o), std::runtime_error);  // nobody would read it
}

TEST(Process, RunsThisBinaryAgain) {
  ProcessOptions o;
  o.out = Sink::Capture;
  const ProcessResult r = run_self({"--gtest_list_tests", "--gtest_filter=Process.RunsThisBinaryAgain"}, o);
  EXPECT_TRUE(r.ok());
  EXPECT_NE(r.out.find("RunsThisBinaryAgain"), std::string::npos) << r.out;
}

TEST(Process, AForkedFunctionSendsItsResultBack) {
  const std::string big(3u << 20, 'y');
  ForkedResult r = run_forked([&] { return big; });
  EXPECT_EQ(r.status, 0);
  EXPECT_TRUE(r.out == big);
  r = run_forked([]() -> std::string { throw std::runtime_error("no"); });
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.out, "");
  r = run_forked([]() -> std::string { _exit(4); });
  EXPECT_EQ(exit_code(r.status), 4);
}

// The shell reads a quoted word back as the same single word, whatever it holds.
TEST(Process, ShellQuoteSurvivesTheShell) {
  for (const std::string word : {"plain.fst", "with space.fst", "it's.fst", "a'b'\"c\" $HOME `x` ;rm.fst", ""}) {
    SCOPED_TRACE(word);
    ProcessOptions o;
    o.out = Sink::Capture;
    const ProcessResult r = run_process({"/bin/sh", "-c", "printf '%s|' " + shell_quote(word)}, o);
    EXPECT_TRUE(r.ok());
    EXPECT_EQ(r.out, word + "|");
  }
}

}  // namespace
}  // namespace rastsim
