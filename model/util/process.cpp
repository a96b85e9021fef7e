// SPDX-License-Identifier: Apache-2.0
#include "util/process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "util/interrupt.h"

namespace rastsim {

namespace {

std::string errno_text() { return std::strerror(errno); }

// A descriptor closed with its owner.
class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(Fd&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
  Fd& operator=(Fd&& o) noexcept {
    if (this != &o) reset(), fd_ = o.fd_, o.fd_ = -1;
    return *this;
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  void reset() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

// A pipe, both ends close-on-exec: [0] read, [1] write.
std::pair<Fd, Fd> make_pipe() {
  int fd[2];
  if (pipe2(fd, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed: " + errno_text());
  return {Fd(fd[0]), Fd(fd[1])};
}

Fd open_file(const std::string& path, int flags) {
  const int fd = open(path.c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(path + ": cannot open for a child process: " + errno_text());
  return Fd(fd);
}

void flush_output() {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
}

// Everything the child does between fork and exec, prepared before the fork (after it,
// only async-signal-safe calls: another thread may hold the allocator's lock).
struct Launch {
  std::string file;           // what to execute
  bool search_path = true;    // execvp (a name without '/') or execv
  std::vector<std::string> argv;
  std::string cant_run;       // "cannot run NAME: "
  std::string cwd;
  int fds[3] = {-1, -1, -1};  // what descriptors 0, 1, 2 become (-1: kept)
  bool err_to_out = false;    // 2 becomes whatever 1 is
  bool die_with_parent = false;
};

[[noreturn]] void fail_in_child(const Launch& l) {
  const char* why = strerrordesc_np(errno);
  const auto put = [](const char* s) {
    for (size_t n = std::strlen(s); n > 0;) {
      const ssize_t w = write(2, s, n);
      if (w <= 0) return;
      s += w, n -= size_t(w);
    }
  };
  put(l.cant_run.c_str());
  put(why ? why : "unknown error");
  put("\n");
  _exit(127);
}

// The signals interrupt.h handles, blocked in the parent from before the fork until the
// child's process group is registered (a signal in between would miss the child), and in
// the child until their handlers are back to the default.
class BlockInterrupts {
 public:
  BlockInterrupts() {
    sigset_t s;
    sigemptyset(&s);
    for (int sig : kInterruptSignals) sigaddset(&s, sig);
    pthread_sigmask(SIG_BLOCK, &s, &old_);
  }
  ~BlockInterrupts() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockInterrupts(const BlockInterrupts&) = delete;
  BlockInterrupts& operator=(const BlockInterrupts&) = delete;
  const sigset_t& old() const { return old_; }

 private:
  sigset_t old_;
};

// After fork, in the child (async-signal-safe calls only): a process group of its own,
// whose every process interrupt.h's handler stops, and this process's handlers undone.
void detach_child(const sigset_t& mask) {
  setpgid(0, 0);
  default_interrupt_actions();
  sigprocmask(SIG_SETMASK, &mask, nullptr);
}

[[noreturn]] void exec_in_child(const Launch& l, const std::vector<char*>& argv, pid_t parent, const sigset_t& mask) {
  detach_child(mask);
  if (l.die_with_parent) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1);  // it died before the line above
  }
  for (int k = 0; k < 3; ++k) {
    if (l.fds[k] < 0) continue;
    if (l.fds[k] == k) fcntl(k, F_SETFD, 0);  // already in place: only keep it open across exec
    else dup2(l.fds[k], k);
  }
  if (l.err_to_out) dup2(1, 2);
  if (!l.cwd.empty() && chdir(l.cwd.c_str()) != 0) fail_in_child(l);
  if (l.search_path) execvp(l.file.c_str(), argv.data());
  else execv(l.file.c_str(), argv.data());
  fail_in_child(l);
}

pid_t launch(const Launch& l) {
  std::vector<char*> argv;
  for (const auto& a : l.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  throw_if_interrupted();  // no new child once interrupted
  flush_output();
  const BlockInterrupts blocked;
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed: " + errno_text());
  if (pid == 0) exec_in_child(l, argv, parent, blocked.old());
  setpgid(pid, pid);  // as the child does: whichever runs first
  register_child_group(pid);
  return pid;
}

Launch launch_of(const std::vector<std::string>& argv, const ProcessOptions& o) {
  if (argv.empty() || argv[0].empty()) throw std::runtime_error("run_process: no program to run");
  Launch l;
  l.file = argv[0];
  l.argv = argv;
  l.cant_run = "cannot run " + argv[0] + ": ";
  l.cwd = o.cwd;
  l.die_with_parent = o.die_with_parent;
  l.err_to_out = o.err == Sink::Stdout;
  return l;
}

Launch self_launch(const std::vector<std::string>& args, const ProcessOptions& o) {
  std::vector<std::string> argv{"rastsim"};
  argv.insert(argv.end(), args.begin(), args.end());
  Launch l = launch_of(argv, o);
  l.file = "/proc/self/exe";
  l.search_path = false;
  return l;
}

// The descriptors a child's streams are redirected to, held by the parent until the
// child has them (then closed), and the parent's ends of the pipes.
struct Streams {
  Fd child[3];
  Fd feed;             // stdin's socket (o.feed_input)
  Fd read_out, read_err;  // Sink::Capture / Sink::Lines
};

// stdout (k = 1) or stderr (k = 2) per its sink.
void sink_stream(Streams& s, int k, Sink sink, const std::string& path) {
  Fd& parent_end = k == 1 ? s.read_out : s.read_err;
  switch (sink) {
    case Sink::Inherit:
    case Sink::Stdout:
      return;
    case Sink::Null:
      s.child[k] = open_file("/dev/null", O_WRONLY);
      return;
    case Sink::File:
      s.child[k] = open_file(path, O_WRONLY | O_CREAT | O_TRUNC);
      return;
    case Sink::Capture:
    case Sink::Lines: {
      auto [r, w] = make_pipe();
      parent_end = std::move(r);
      s.child[k] = std::move(w);
      return;
    }
  }
}

Streams open_streams(const ProcessOptions& o, bool waiting) {
  if (!waiting && (o.feed_input || o.out == Sink::Capture || o.out == Sink::Lines || o.err == Sink::Capture ||
                   o.err == Sink::Lines))
    throw std::runtime_error("start_process: a child not waited for cannot be fed or read");
  if (o.out == Sink::Stdout) throw std::runtime_error("run_process: stdout cannot go to stdout");
  Streams s;
  if (o.feed_input) {
    // A socket, not a pipe: send(MSG_NOSIGNAL) to a child that stopped reading is an
    // error to ignore, not a SIGPIPE that kills this process.
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
      throw std::runtime_error("socketpair failed: " + errno_text());
    s.feed = Fd(sv[0]), s.child[0] = Fd(sv[1]);
  } else if (o.stdin_null) {
    s.child[0] = open_file("/dev/null", O_RDONLY);
  }
  sink_stream(s, 1, o.out, o.out_path);
  sink_stream(s, 2, o.err, o.err_path);
  return s;
}

pid_t start(Launch l, Streams& s) {
  for (int k = 0; k < 3; ++k) l.fds[k] = s.child[k].get();
  const pid_t pid = launch(l);
  for (auto& fd : s.child) fd.reset();  // the child's now; a pipe ends when the child closes it
  return pid;
}

// Splits one stream's bytes into lines for on_line.
struct LineSplitter {
  std::string pending;
  void add(const char* p, size_t n, const std::function<void(const std::string&)>& on_line) {
    pending.append(p, n);
    size_t from = 0;
    for (size_t nl; (nl = pending.find('\n', from)) != std::string::npos; from = nl + 1)
      on_line(pending.substr(from, nl - from));
    pending.erase(0, from);
  }
  void finish(const std::function<void(const std::string&)>& on_line) {
    if (!pending.empty()) on_line(pending);
    pending.clear();
  }
};

// Feeds o.input to the child and reads its captured streams until both are closed.
void pump(Streams& s, const ProcessOptions& o, ProcessResult& r) {
  size_t fed = 0;
  if (s.feed.get() >= 0 && o.input.empty()) s.feed.reset();
  LineSplitter lines[2];
  Fd* reads[2] = {&s.read_out, &s.read_err};
  const Sink sinks[2] = {o.out, o.err};
  std::string* captured[2] = {&r.out, &r.err};
  char buf[65536];
  while (s.feed.get() >= 0 || s.read_out.get() >= 0 || s.read_err.get() >= 0) {
    pollfd p[3] = {{s.feed.get(), POLLOUT, 0}, {s.read_out.get(), POLLIN, 0}, {s.read_err.get(), POLLIN, 0}};
    if (poll(p, 3, -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("poll failed: " + errno_text());
    }
    if (p[0].revents) {
      const ssize_t w = send(s.feed.get(), o.input.data() + fed, o.input.size() - fed, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (w > 0) fed += size_t(w);
      if ((w < 0 && errno != EAGAIN && errno != EINTR) || fed == o.input.size()) s.feed.reset();
    }
    for (int k = 0; k < 2; ++k) {
      if (!p[k + 1].revents) continue;
      const ssize_t n = read(reads[k]->get(), buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        if (sinks[k] == Sink::Lines) lines[k].finish(o.on_line);
        reads[k]->reset();
      } else if (sinks[k] == Sink::Lines) {
        lines[k].add(buf, size_t(n), o.on_line);
      } else {
        captured[k]->append(buf, size_t(n));
      }
    }
  }
}

}  // namespace

bool ProcessResult::ok() const { return WIFEXITED(status) && WEXITSTATUS(status) == 0; }

namespace {

ProcessResult run_launch(const Launch& l, const ProcessOptions& o) {
  if ((o.out == Sink::Lines || o.err == Sink::Lines) && !o.on_line)
    throw std::runtime_error("run_process: Sink::Lines without on_line");
  Streams s = open_streams(o, true);
  ProcessResult r;
  const pid_t pid = start(l, s);
  const InterruptScope scope;  // a signal stops the child (interrupt.h), then wait_process throws
  try {
    pump(s, o, r);
  } catch (...) {
    s.feed.reset(), s.read_out.reset(), s.read_err.reset();  // the child sees EOF or EPIPE and ends
    stop_process(pid);
    throw;
  }
  r.status = wait_process(pid);
  return r;
}

pid_t start_launch(const Launch& l, const ProcessOptions& o) {
  Streams s = open_streams(o, false);
  return start(l, s);
}

}  // namespace

ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& o) {
  return run_launch(launch_of(argv, o), o);
}

pid_t start_process(const std::vector<std::string>& argv, const ProcessOptions& o) {
  return start_launch(launch_of(argv, o), o);
}

ProcessResult run_self(const std::vector<std::string>& args, const ProcessOptions& o) {
  return run_launch(self_launch(args, o), o);
}

pid_t start_self(const std::vector<std::string>& args, const ProcessOptions& o) {
  return start_launch(self_launch(args, o), o);
}

ProcessOptions worker_options(const std::string& err_path) {
  ProcessOptions o;
  o.out = Sink::Null;
  o.err = Sink::File;
  o.err_path = err_path;
  o.die_with_parent = true;
  return o;
}

int wait_process(pid_t pid) {
  const InterruptScope scope;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed: " + errno_text());
  unregister_child_group(pid);
  throw_if_interrupted();
  return status;
}

std::pair<pid_t, int> wait_any_process() {
  const InterruptScope scope;
  int status = 0;
  pid_t pid;
  while ((pid = waitpid(-1, &status, 0)) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed: " + errno_text());
  unregister_child_group(pid);
  throw_if_interrupted();
  return {pid, status};
}

void stop_process(pid_t pid) noexcept {
  kill(-pid, SIGTERM);
  kill(pid, SIGTERM);  // in case it had not yet made its own group
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  unregister_child_group(pid);
}

int exit_code(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

std::string status_text(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status))
    return "signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "status " + std::to_string(status);
}

ForkedResult run_forked(const std::function<std::string()>& fn) {
  auto [r, w] = make_pipe();
  throw_if_interrupted();
  flush_output();
  pid_t pid;
  {
    const BlockInterrupts blocked;
    pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed: " + errno_text());
    if (pid == 0) {
      setpgid(0, 0);
      reset_interrupt_handling_in_child();  // the parent's files and children are not its own
      sigprocmask(SIG_SETMASK, &blocked.old(), nullptr);
    } else {
      setpgid(pid, pid);
      register_child_group(pid);
    }
  }
  if (pid == 0) {
    r.reset();
    std::string out;
    try {
      out = fn();
    } catch (...) {
      _exit(1);
    }
    for (size_t done = 0; done < out.size();) {
      const ssize_t n = write(w.get(), out.data() + done, out.size() - done);
      if (n <= 0) _exit(1);
      done += size_t(n);
    }
    _exit(0);  // no atexit handlers, no stream flushes: the parent owns the process's output
  }
  w.reset();
  Streams s;
  s.read_out = std::move(r);
  ProcessOptions o;
  o.out = Sink::Capture;
  ProcessResult res;
  const InterruptScope scope;
  try {
    pump(s, o, res);
  } catch (...) {
    stop_process(pid);
    throw;
  }
  return {wait_process(pid), std::move(res.out)};
}

std::string find_program(const std::string& name) {
  const auto runnable = [](const std::string& p) {
    struct stat st {};
    return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(p.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) return runnable(name) ? name : "";
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  for (std::string d; std::getline(ss, d, ':');) {
    const std::string p = (d.empty() ? std::string(".") : d) + "/" + name;
    if (runnable(p)) return p;
  }
  return "";
}

std::string last_line(const std::string& path) {
  std::ifstream is(path);
  std::string line, last;
  while (std::getline(is, line))
    if (!line.empty()) last = line;
  return last.empty() ? "(no message)" : last;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string shell_command(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) {
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789_./=:,+-@%") == std::string::npos;
    line += (line.empty() ? "" : " ") + (plain ? a : shell_quote(a));
  }
  return line;
}

std::vector<std::string> this_command_line() {
  std::ifstream is("/proc/self/cmdline", std::ios::binary);
  std::vector<std::string> argv;
  for (std::string a; std::getline(is, a, '\0');) argv.push_back(a);
  return argv;
}

}  // namespace rastsim
