// SPDX-License-Identifier: Apache-2.0
// `rastsim sweep --backend local` (sweep.h): the points as child processes of this same
// binary, a number at a time, with a progress bar on a terminal; stopped, children and
// all, by SIGINT or SIGTERM (util/interrupt.h).
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

#include "sweep/sweep.h"
#include "util/process.h"

namespace rastsim::sweep {

namespace {

class Progress {
 public:
  explicit Progress(size_t total) : total_(total), tty_(isatty(2)) {}
  void update(size_t done, size_t failed, const std::string& what) {
    if (tty_) {
      const int width = 30, filled = int(width * done / std::max<size_t>(total_, 1));
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << done << "/"
                << total_ << (failed ? " (" + std::to_string(failed) + " failed)" : "") << std::flush;
      if (done == total_) std::cerr << "\n";
    } else {
      std::cerr << "sweep: " << done << "/" << total_ << " " << what << "\n";
    }
  }
  bool tty() const { return tty_; }

 private:
  size_t total_;
  bool tty_;
};

// The points' processes still running, stopped when the sweep stops early: an
// interruption (util/interrupt.h: wait_any_process throws) or an error.
class Running : public std::map<pid_t, size_t> {
 public:
  Running() = default;
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;
  ~Running() {
    for (const auto& entry : *this) stop_process(entry.first);
  }
};

}  // namespace

size_t run_local(std::vector<Point>& points, const std::vector<size_t>& todo, const std::vector<Axis>& axes,
                 unsigned jobs, const std::filesystem::path& tmp, const OnDone& on_done) {
  Progress progress(todo.size());
  Running running;
  const auto file = [&](size_t i, const char* ext) { return (tmp / (std::to_string(i) + ext)).string(); };
  size_t next = 0, done = 0, failed = 0;
  while (done < todo.size()) {
    while (next < todo.size() && running.size() < jobs) {
      const size_t i = todo[next++];
      std::vector<std::string> args = points[i].args;
      args.insert(args.end(), {"--stats", file(i, ".json")});
      running[start_self(args, worker_options(file(i, ".err")))] = i;
    }
    const auto [pid, status] = wait_any_process();
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    Point& p = points[it->second];
    const size_t i = it->second;
    running.erase(it);
    ++done;
    p.status = exit_code(status);
    if (p.status == 0) {
      std::ifstream is(file(i, ".json"));
      p.stats = nlohmann::json::parse(is);
    } else {
      ++failed;
      p.error = last_line(file(i, ".err"));
      if (progress.tty()) std::cerr << "\n";
      std::cerr << "sweep: point " << describe(p, axes) << " failed: " << p.error << "\n";
    }
    std::filesystem::remove(file(i, ".json")), std::filesystem::remove(file(i, ".err"));
    on_done(i);
    progress.update(done, failed, describe(p, axes) + (p.status == 0 ? " ok" : " FAILED"));
  }
  return failed;
}

}  // namespace rastsim::sweep
