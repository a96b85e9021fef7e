// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep --backend slurm` (sweep.h): the points as Slurm job arrays, a task a point,
// each task this same binary writing its stats and exit status to files in a work
// directory; squeue polled until the arrays are done, the rows gathered as they appear.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "sweep.h"

namespace rastsim::app::sweep {

namespace fs = std::filesystem;

namespace {

struct ToolResult {
  int status = -1;
  std::string out, err;
};

// Runs a Slurm command (found on PATH), its stdout and stderr through files in `dir`.
ToolResult run_tool(const std::vector<std::string>& args, const fs::path& dir) {
  const std::string out_path = (dir / "tool.out").string(), err_path = (dir / "tool.err").string();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) _exit(126);
    dup2(in, 0), dup2(out, 1), dup2(err, 2);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    std::fprintf(stderr, "%s: %s\n", args[0].c_str(), std::strerror(errno));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed");
  ToolResult r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  const auto slurp = [](const std::string& p) {
    std::ifstream is(p);
    return std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  };
  r.out = slurp(out_path), r.err = slurp(err_path);
  return r;
}

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(s.begin());
  return s;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The cluster's MaxArraySize (task ids run 0 to MaxArraySize - 1); Slurm's default 1001.
size_t max_array_size(const fs::path& dir) {
  const ToolResult r = run_tool({"scontrol", "show", "config"}, dir);
  std::istringstream is(r.out);
  for (std::string line; std::getline(is, line);)
    if (line.rfind("MaxArraySize", 0) == 0 && line.find('=') != std::string::npos)
      try {
        return std::max<size_t>(1, std::stoul(line.substr(line.find('=') + 1)));
      } catch (const std::exception&) {
      }
  return 1001;
}

// The job script: task T (array index + the offset in $1) runs point todo[T].
void write_script(const fs::path& path, const std::vector<Point>& points, const std::vector<size_t>& todo,
                  const fs::path& dir) {
  std::ofstream os(path);
  os << "#!/bin/sh\n# rastsim sweep --backend slurm: one array task a sweep point.\n"
     << "t=$((SLURM_ARRAY_TASK_ID + $1))\ncase $t in\n";
  for (size_t t = 0; t < todo.size(); ++t) {
    os << t << ") set --";
    for (const auto& a : points[todo[t]].args) os << " " << shell_quote(a);
    os << " ;;\n";
  }
  os << "*) echo \"rastsim sweep: no task $t\" >&2; exit 2 ;;\nesac\n"
     << "d=" << shell_quote(dir.string()) << "\n"
     << shell_quote(fs::read_symlink("/proc/self/exe").string()) << " \"$@\" --stats \"$d/$t.json\" 2> \"$d/$t.err\"\n"
     << "echo $? > \"$d/$t.rc.tmp\" && mv \"$d/$t.rc.tmp\" \"$d/$t.rc\"\n";
  if (!os) throw std::runtime_error(path.string() + ": write failed");
}

void on_signal(int) { interrupted = 1; }

// SIGINT and SIGTERM set `interrupted` (no SA_RESTART: a sleep returns early) while alive.
class InterruptGuard {
 public:
  InterruptGuard() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_), sigaction(SIGTERM, &sa, &old_term_);
    interrupted = 0;
  }
  ~InterruptGuard() { sigaction(SIGINT, &old_int_, nullptr), sigaction(SIGTERM, &old_term_, nullptr); }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

struct Task {
  size_t point;
  std::string job;  // Slurm job id of its array
  size_t index;     // its index in that array
  bool done = false;
};

}  // namespace

size_t run_slurm(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 const SweepSlurmOptions& o, const std::string& out_path, const OnDone& on_done) {
  if (todo.empty()) return 0;
  const fs::path work = fs::absolute(o.workdir.empty() ? out_path + ".slurm" : o.workdir);
  const fs::path dir = work / ("sweep-" + std::to_string(std::time(nullptr)) + "-" + std::to_string(getpid()));
  fs::create_directories(dir);
  write_script(dir / "array.sh", points, todo, dir);

  // Submit: arrays of at most MaxArraySize tasks.
  const size_t chunk = max_array_size(dir);
  std::vector<Task> tasks;
  std::vector<std::string> jobs;
  for (size_t first = 0; first < todo.size(); first += chunk) {
    const size_t n = std::min(chunk, todo.size() - first);
    std::vector<std::string> args{"sbatch", "--parsable", "--job-name=rastsim-sweep",
                                  "--array=0-" + std::to_string(n - 1),
                                  "--output=" + (dir / "slurm-%A_%a.out").string()};
    if (!o.partition.empty()) args.push_back("--partition=" + o.partition);
    if (!o.time.empty()) args.push_back("--time=" + o.time);
    args.insert(args.end(), o.sbatch_args.begin(), o.sbatch_args.end());
    args.insert(args.end(), {(dir / "array.sh").string(), std::to_string(first)});
    const ToolResult r = run_tool(args, dir);
    const std::string job = trimmed(r.out.substr(0, r.out.find(';')));
    if (r.status != 0 || job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
      for (const auto& j : jobs) run_tool({"scancel", j}, dir);
      throw std::runtime_error("sbatch failed: " + trimmed(r.err.empty() ? r.out : r.err));
    }
    jobs.push_back(job);
    for (size_t a = 0; a < n; ++a) tasks.push_back({todo[first + a], job, a});
    std::cerr << "sweep: submitted Slurm job array " << job << " (" << n << " tasks)\n";
  }
  std::string job_list;
  for (const auto& j : jobs) job_list += (job_list.empty() ? "" : ",") + j;

  // Gathers every task whose result file has appeared; returns how many did this call.
  size_t finished = 0, failed = 0;
  const auto report = [&](size_t t, int status, const std::string& error) {
    Task& task = tasks[t];
    Point& p = points[task.point];
    task.done = true;
    ++finished;
    p.status = status;
    p.error = error;
    if (status == 0) {
      try {
        p.stats = nlohmann::json::parse(std::ifstream(dir / (std::to_string(t) + ".json")));
      } catch (const std::exception& e) {
        p.status = 1, p.error = std::string("unreadable stats: ") + e.what();
      }
    }
    if (p.status != 0) {
      ++failed;
      std::cerr << "sweep: point " << describe(p, axes) << " failed (Slurm task " << task.job << "_" << task.index
                << "): " << p.error << "\n";
    }
    on_done(task.point);
  };
  const auto gather = [&] {
    for (size_t t = 0; t < tasks.size(); ++t) {
      if (tasks[t].done) continue;
      std::ifstream rc(dir / (std::to_string(t) + ".rc"));
      int status = -1;
      if (!(rc >> status)) continue;
      report(t, status, status == 0 ? "" : last_line((dir / (std::to_string(t) + ".err")).string()));
    }
  };

  // Wait: squeue until none of the tasks is queued, running or completing.
  InterruptGuard guard;
  const bool tty = isatty(2);
  std::string last_progress;
  int squeue_failures = 0;
  for (;;) {
    gather();
    const ToolResult q = run_tool({"squeue", "-h", "-r", "-j", job_list, "-o", "%i %T"}, dir);
    size_t running = 0, pending = 0, queued = 0;
    if (q.status != 0 && q.err.find("Invalid job id") == std::string::npos) {
      if (++squeue_failures == 30) throw std::runtime_error("squeue keeps failing: " + trimmed(q.err));
      queued = 1;  // unknown: keep waiting
    } else {
      squeue_failures = 0;
      std::istringstream is(q.status == 0 ? q.out : "");
      for (std::string id, state; is >> id >> state;) {
        ++queued;
        if (state == "RUNNING" || state == "COMPLETING") ++running;
        else if (state == "PENDING") ++pending;
      }
    }
    const std::string progress = "sweep: Slurm " + job_list + ": " + std::to_string(finished) + "/" +
                                 std::to_string(tasks.size()) + " done" +
                                 (failed ? " (" + std::to_string(failed) + " failed)" : "") + ", " +
                                 std::to_string(running) + " running, " + std::to_string(pending) + " pending";
    if (progress != last_progress) std::cerr << (tty ? "\r\033[K" : "") << progress << (tty ? "" : "\n") << std::flush;
    last_progress = progress;
    if (queued == 0 || finished == tasks.size()) break;
    for (double slept = 0; slept < o.poll_seconds && !interrupted; slept += 0.1)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (interrupted) {
      run_tool({"scancel", job_list}, dir);
      gather();
      if (tty) std::cerr << "\n";
      throw std::runtime_error("interrupted: Slurm job " + job_list + " cancelled; the " +
                               std::to_string(finished) + " finished rows are in " + out_path +
                               " (run again with --resume for the rest)");
    }
  }
  if (tty) std::cerr << "\n";

  // Tasks that left the queue without a result: their result file may lag on a shared
  // filesystem, so look again for a while; then the Slurm output says why.
  for (int wait = 0; finished < tasks.size() && wait < 10; ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(wait == 0 ? 0 : 500));
    gather();
  }
  for (size_t t = 0; t < tasks.size(); ++t) {
    if (tasks[t].done) continue;
    const fs::path out = dir / ("slurm-" + tasks[t].job + "_" + std::to_string(tasks[t].index) + ".out");
    std::string why = fs::exists(out) ? last_line(out.string()) : "(no message)";
    if (why == "(no message)") {
      const ToolResult s = run_tool({"sacct", "-n", "-X", "-P", "-o", "State",
                                     "-j", tasks[t].job + "_" + std::to_string(tasks[t].index)}, dir);
      why = "the task ended without a result" + (s.status == 0 && !trimmed(s.out).empty()
                                                    ? " (Slurm state " + trimmed(s.out) + ")"
                                                    : std::string(" (no Slurm output)"));
    }
    report(t, 1, why);
  }
  if (failed == 0) {
    fs::remove_all(dir);
    std::error_code ec;
    fs::remove(work, ec);  // only when empty
  } else {
    std::cerr << "sweep: the failed tasks' files are in " << dir.string() << "\n";
  }
  return failed;
}

}  // namespace rastsim::app::sweep
