// SPDX-License-Identifier: Apache-2.0
// Child processes, the one way rastsim runs another program: an argv vector executed
// directly (no shell, so no quoting), with its standard streams inherited, discarded,
// redirected to files, captured into strings or read line by line, and its stdin
// optionally fed from a string. Also this same binary as a child (/proc/self/exe: SystemC
// elaborates one design per process) and a function run in a forked child that sends a
// string back (run_forked).
//
// - A program name without '/' is searched on PATH (execvp). One that cannot be started
//   exits 127 after printing "cannot run NAME: REASON" on its stderr, as a shell would.
// - The parent's buffered output is flushed before a fork, so neither process repeats it
//   and it comes before the child's.
// - Descriptors are opened close-on-exec: a child started from one thread does not hold
//   another thread's pipe open (area.cpp runs Yosys from two threads at once).
// - Each child leads a process group of its own, registered with interrupt.h: on SIGINT or
//   SIGTERM the whole group (a compiler under `cmake --build`) gets SIGTERM, and the waits
//   below throw Interrupted once the child has ended; no child starts after a signal.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace rastsim {

// Where a child's stdout or stderr goes.
enum class Sink {
  Inherit,  // this process's stream
  Null,     // /dev/null
  File,     // a file (created or truncated): ProcessOptions::out_path / err_path
  Capture,  // a string of ProcessResult (run_process only)
  Lines,    // each line to ProcessOptions::on_line as it arrives (run_process only)
  Stdout,   // stderr only: wherever stdout goes (2>&1)
};

struct ProcessOptions {
  std::string cwd;  // the child's working directory ("" = this process's)
  // stdin: this process's, unless `input` is fed (then closed) or stdin_null.
  bool feed_input = false;
  std::string input;
  bool stdin_null = false;
  Sink out = Sink::Inherit, err = Sink::Inherit;
  std::string out_path, err_path;  // Sink::File
  // Sink::Lines: called with each line (no '\n'; a last unterminated line too), stdout's
  // and stderr's alike when both are Lines or stderr is Stdout.
  std::function<void(const std::string&)> on_line;
  bool die_with_parent = false;  // SIGTERM to the child when this process dies
};

struct ProcessResult {
  int status = 0;        // the wait status (waitpid)
  std::string out, err;  // Sink::Capture
  bool ok() const;       // exited with status 0
};

// Runs argv[0] with `argv` and waits for it. Throws std::runtime_error when it cannot
// fork or a redirection file cannot be opened; a program that is not found is exit 127.
ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& o = {});

// Starts argv[0] without waiting (stdout and stderr Inherit, Null or File only); returns
// its pid for wait_process / wait_any_process.
pid_t start_process(const std::vector<std::string>& argv, const ProcessOptions& o = {});

// As run_process / start_process, running this binary (/proc/self/exe) as
// `rastsim ARGS...` (args[0] is the subcommand).
ProcessResult run_self(const std::vector<std::string>& args, const ProcessOptions& o = {});
pid_t start_self(const std::vector<std::string>& args, const ProcessOptions& o = {});

// A worker run of this binary (SystemC elaborates one design per process, so a command
// that needs several simulations runs each in a child): stdout discarded, stderr to
// `err_path`, SIGTERM when this process dies (a killed sweep leaves none running on).
ProcessOptions worker_options(const std::string& err_path);

// The wait status of the child `pid` (started here), once it has ended. Throws
// Interrupted (interrupt.h) when a signal came meanwhile.
int wait_process(pid_t pid);
// Any child that ends: its pid and wait status. Throws when there is none, and Interrupted
// (the child reaped, its status lost) when a signal came meanwhile.
std::pair<pid_t, int> wait_any_process();
// Ends the child `pid`: SIGTERM to its process group, then reaped (one reaped already is
// passed over). For cleanup: never throws.
void stop_process(pid_t pid) noexcept;

// A wait status as a shell's $?: the exit status, or 128 + the signal that ended it.
int exit_code(int status);
// "exit status 1", "signal 9 (Killed)".
std::string status_text(int status);

// Runs fn in a forked child and returns what it returned (the child writes it to a pipe
// and exits 0 at once, skipping atexit handlers: the parent owns the process's output).
// `status` is the child's wait status; an exception from fn is the child's to catch.
struct ForkedResult {
  int status = 0;
  std::string out;
};
ForkedResult run_forked(const std::function<std::string()>& fn);

// The executable `name` as execvp would find it on PATH, or "" when none is.
std::string find_program(const std::string& name);

// The last non-empty line of a file (a child's error message), or "(no message)".
std::string last_line(const std::string& path);

// `s` as one word for /bin/sh: single-quoted, each ' written as '\''. Only for a script
// written to a file for a shell to run later (the Slurm backend's job script); nothing
// here runs a shell.
std::string shell_quote(const std::string& s);
// A command line to show a user (one to copy and run): the words separated by spaces,
// each shell_quote()d only when it holds a character a shell would read specially.
std::string shell_command(const std::vector<std::string>& argv);

// This process's own argv, as it was started (/proc/self/cmdline).
std::vector<std::string> this_command_line();

}  // namespace rastsim
