// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep --backend slurm` (sweep.h): the points as Slurm job arrays, a task a point,
// each task this same binary writing its stats and exit status to files in a work
// directory; squeue polled until the arrays are done, the rows gathered as they appear.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <csignal>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "sweep/sweep.h"
#include "util/process.h"

namespace rastsim::sweep {

namespace fs = std::filesystem;

namespace {

struct ToolResult {
  int status = -1;  // exit status (128 + signal when killed)
  std::string out, err;
};

// Runs a Slurm command (found on PATH), stdin from /dev/null, its stdout and stderr captured.
ToolResult run_tool(const std::vector<std::string>& args) {
  ProcessOptions po;
  po.stdin_null = true;
  po.out = po.err = Sink::Capture;
  ProcessResult r = run_process(args, po);
  return {exit_code(r.status), std::move(r.out), std::move(r.err)};
}

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(s.begin());
  return s;
}

// The cluster's MaxArraySize (task ids run 0 to MaxArraySize - 1); Slurm's default 1001.
size_t max_array_size() {
  const ToolResult r = run_tool({"scontrol", "show", "config"});
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

// Task counts of one squeue poll.
struct QueueState {
  size_t running = 0, pending = 0, queued = 0;
};

// One sweep's Slurm run: submit the arrays, wait for them while gathering each task's
// result as its file appears, then account for the tasks that left none.
class SlurmRun {
 public:
  SlurmRun(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
           const SlurmOptions& o, const std::string& out_path, const OnDone& on_done)
      : points_(points), todo_(todo), axes_(axes), o_(o), out_path_(out_path), on_done_(on_done),
        work_(fs::absolute(o.workdir.empty() ? out_path + ".slurm" : o.workdir)),
        dir_(work_ / ("sweep-" + std::to_string(std::time(nullptr)) + "-" + std::to_string(getpid()))) {}

  size_t run() {
    fs::create_directories(dir_);
    write_script(dir_ / "array.sh", points_, todo_, dir_);
    submit();
    wait();
    settle();
    if (failed_ == 0) {
      fs::remove_all(dir_);
      std::error_code ec;
      fs::remove(work_, ec);  // only when empty
    } else {
      std::cerr << "sweep: the failed tasks' files are in " << dir_.string() << "\n";
    }
    return failed_;
  }

 private:
  // Arrays of at most MaxArraySize tasks.
  void submit() {
    const size_t chunk = max_array_size();
    std::vector<std::string> jobs;
    for (size_t first = 0; first < todo_.size(); first += chunk) {
      const size_t n = std::min(chunk, todo_.size() - first);
      std::vector<std::string> args{"sbatch", "--parsable", "--job-name=rastsim-sweep",
                                    "--array=0-" + std::to_string(n - 1),
                                    "--output=" + (dir_ / "slurm-%A_%a.out").string()};
      if (!o_.partition.empty()) args.push_back("--partition=" + o_.partition);
      if (!o_.time.empty()) args.push_back("--time=" + o_.time);
      args.insert(args.end(), o_.sbatch_args.begin(), o_.sbatch_args.end());
      args.insert(args.end(), {(dir_ / "array.sh").string(), std::to_string(first)});
      const ToolResult r = run_tool(args);
      const std::string job = trimmed(r.out.substr(0, r.out.find(';')));
      if (r.status != 0 || job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
        for (const auto& j : jobs) run_tool({"scancel", j});
        throw std::runtime_error("sbatch failed: " + trimmed(r.err.empty() ? r.out : r.err));
      }
      jobs.push_back(job);
      for (size_t a = 0; a < n; ++a) tasks_.push_back({todo_[first + a], job, a});
      std::cerr << "sweep: submitted Slurm job array " << job << " (" << n << " tasks)\n";
    }
    for (const auto& j : jobs) job_list_ += (job_list_.empty() ? "" : ",") + j;
  }

  // Task t has finished with `status`: its point gets its stats (or error) and its row.
  void report(size_t t, int status, const std::string& error) {
    Task& task = tasks_[t];
    Point& p = points_[task.point];
    task.done = true;
    ++finished_;
    p.status = status;
    p.error = error;
    if (status == 0) {
      try {
        p.stats = nlohmann::json::parse(std::ifstream(dir_ / (std::to_string(t) + ".json")));
      } catch (const std::exception& e) {
        p.status = 1, p.error = std::string("unreadable stats: ") + e.what();
      }
    }
    if (p.status != 0) {
      ++failed_;
      std::cerr << "sweep: point " << describe(p, axes_) << " failed (Slurm task " << task.job << "_" << task.index
                << "): " << p.error << "\n";
    }
    on_done_(task.point);
  }

  // Every task whose result file has appeared.
  void gather() {
    for (size_t t = 0; t < tasks_.size(); ++t) {
      if (tasks_[t].done) continue;
      std::ifstream rc(dir_ / (std::to_string(t) + ".rc"));
      int status = -1;
      if (!(rc >> status)) continue;
      report(t, status, status == 0 ? "" : last_line((dir_ / (std::to_string(t) + ".err")).string()));
    }
  }

  QueueState poll_queue() {
    const ToolResult q = run_tool({"squeue", "-h", "-r", "-j", job_list_, "-o", "%i %T"});
    QueueState s;
    if (q.status != 0 && q.err.find("Invalid job id") == std::string::npos) {
      if (++squeue_failures_ == 30) throw std::runtime_error("squeue keeps failing: " + trimmed(q.err));
      s.queued = 1;  // unknown: keep waiting
      return s;
    }
    squeue_failures_ = 0;
    std::istringstream is(q.status == 0 ? q.out : "");
    for (std::string id, state; is >> id >> state;) {
      ++s.queued;
      if (state == "RUNNING" || state == "COMPLETING") ++s.running;
      else if (state == "PENDING") ++s.pending;
    }
    return s;
  }

  // squeue until none of the tasks is queued, running or completing.
  void wait() {
    InterruptGuard guard;
    const bool tty = isatty(2);
    std::string last_progress;
    for (;;) {
      gather();
      const QueueState q = poll_queue();
      const std::string progress = "sweep: Slurm " + job_list_ + ": " + std::to_string(finished_) + "/" +
                                   std::to_string(tasks_.size()) + " done" +
                                   (failed_ ? " (" + std::to_string(failed_) + " failed)" : "") + ", " +
                                   std::to_string(q.running) + " running, " + std::to_string(q.pending) + " pending";
      if (progress != last_progress) std::cerr << (tty ? "\r\033[K" : "") << progress << (tty ? "" : "\n") << std::flush;
      last_progress = progress;
      if (q.queued == 0 || finished_ == tasks_.size()) break;
      for (double slept = 0; slept < o_.poll_seconds && !interrupted; slept += 0.1)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (interrupted) {
        run_tool({"scancel", job_list_});
        gather();
        if (tty) std::cerr << "\n";
        throw std::runtime_error("interrupted: Slurm job " + job_list_ + " cancelled; the " +
                                 std::to_string(finished_) + " finished rows are in " + out_path_ +
                                 " (run again with --resume for the rest)");
      }
    }
    if (tty) std::cerr << "\n";
  }

  // Tasks that left the queue without a result: their result file may lag on a shared
  // filesystem, so look again for a while; then the Slurm output says why.
  void settle() {
    for (int wait = 0; finished_ < tasks_.size() && wait < 10; ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(wait == 0 ? 0 : 500));
      gather();
    }
    for (size_t t = 0; t < tasks_.size(); ++t)
      if (!tasks_[t].done) report(t, 1, why_no_result(tasks_[t]));
  }

  std::string why_no_result(const Task& task) {
    const std::string id = task.job + "_" + std::to_string(task.index);
    const fs::path out = dir_ / ("slurm-" + id + ".out");
    const std::string why = fs::exists(out) ? last_line(out.string()) : "(no message)";
    if (why != "(no message)") return why;
    const ToolResult s = run_tool({"sacct", "-n", "-X", "-P", "-o", "State", "-j", id});
    return "the task ended without a result" + (s.status == 0 && !trimmed(s.out).empty()
                                                    ? " (Slurm state " + trimmed(s.out) + ")"
                                                    : std::string(" (no Slurm output)"));
  }

  std::vector<Point>& points_;
  const std::vector<size_t>& todo_;
  const std::vector<Axis>& axes_;
  const SlurmOptions& o_;
  const std::string& out_path_;
  const OnDone& on_done_;
  const fs::path work_, dir_;  // the work directory and this sweep's subdirectory
  std::vector<Task> tasks_;
  std::string job_list_;  // the arrays' job ids, comma-separated
  size_t finished_ = 0, failed_ = 0;
  int squeue_failures_ = 0;
};

}  // namespace

size_t run_slurm(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 const SlurmOptions& o, const std::string& out_path, const OnDone& on_done) {
  if (todo.empty()) return 0;
  return SlurmRun(points, todo, axes, o, out_path, on_done).run();
}

}  // namespace rastsim::sweep
