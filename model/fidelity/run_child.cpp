// SPDX-License-Identifier: Apache-2.0
#include "fidelity/run_child.h"

#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace rastsim::fidelity {

nlohmann::json run_in_child_or_error(const std::function<nlohmann::json()>& fn) {
  int fd[2];
  if (pipe(fd) != 0) return {{"error", "pipe failed"}};
  std::cout.flush();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]);
    close(fd[1]);
    return {{"error", "fork failed"}};
  }
  if (pid == 0) {
    close(fd[0]);
    std::string out;
    try {
      out = fn().dump();
    } catch (const std::exception& e) {
      out = nlohmann::json{{"error", e.what()}}.dump();
    }
    for (size_t done = 0; done < out.size();) {
      const ssize_t w = write(fd[1], out.data() + done, out.size() - done);
      if (w <= 0) break;
      done += size_t(w);
    }
    close(fd[1]);
    _exit(0);  // no atexit handlers: the parent owns the process's output
  }
  close(fd[1]);
  std::string in;
  char buf[65536];
  for (ssize_t r; (r = read(fd[0], buf, sizeof buf)) > 0;) in.append(buf, size_t(r));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || in.empty())
    return {{"error", "simulation child died (status " + std::to_string(status) + ")"}};
  return nlohmann::json::parse(in);
}

nlohmann::json run_in_child(const std::function<nlohmann::json()>& fn) {
  nlohmann::json j = run_in_child_or_error(fn);
  if (j.is_object() && j.contains("error")) throw std::runtime_error(j["error"].get<std::string>());
  return j;
}

}  // namespace rastsim::fidelity
