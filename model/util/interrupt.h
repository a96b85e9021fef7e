// SPDX-License-Identifier: Apache-2.0
// SIGINT, SIGTERM and SIGHUP (Ctrl-C, kill, a closed terminal) as a clean stop: no child
// process left running, no temporary file left behind.
//
// install_interrupt_handler() (main) puts one handler on the three signals. It does only
// async-signal-safe things:
// - sends SIGTERM to the process group of every running child (process.h starts each child
//   in a group of its own, so a compiler under `cmake --build` stops with it);
// - outside an InterruptScope: unlinks every registered temporary file (atomic_file.h), then
//   ends the process by the signal, as the default action would have;
// - inside an InterruptScope (a sweep, an RTL build, a wait for a child): only records the
//   signal. The code polls it where it waits (process.h's waits throw Interrupted), and
//   the exception unwinds through the destructors that remove temporary files and folders,
//   up to the one place that says what was kept.
// A second signal while the first one unwinds ends the process at once (after the same
// cleanup). A signal ignored when the handler is installed (`nohup`) stays ignored.
#pragma once

#include <sys/types.h>

#include <csignal>
#include <string>

namespace rastsim {

// Thrown where an interruption stops the program. Not a std::exception, so that the
// handlers that turn a failed step into a message (catch (const std::exception&)) let it
// pass; main() catches it and exits with 128 + the signal, as a shell reports a signal.
class Interrupted {
 public:
  Interrupted(int signal, std::string message) : signal_(signal), message_(std::move(message)) {}
  int signal() const { return signal_; }
  const char* what() const { return message_.c_str(); }

 private:
  int signal_;
  std::string message_;
};

// The signals handled.
inline constexpr int kInterruptSignals[] = {SIGINT, SIGTERM, SIGHUP};

void install_interrupt_handler();

// The signal that interrupted this process, 0 while none has.
int interrupt_signal();
// "SIGINT", "SIGTERM", "SIGHUP" (else "signal N").
std::string signal_name(int signal);
// Throws Interrupted ("interrupted by SIGINT") once a signal has arrived.
void throw_if_interrupted();

// While one is alive, a signal is recorded (and children stopped) instead of ending the
// process: the code it covers polls interrupt_signal() often enough to stop promptly.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

// The registries the handler reads (fixed tables of atomics: registering is lock-free and
// safe against the handler on any thread). A full table registers nothing (-1): that file
// or child is then only cleaned up by unwinding.
//
// A temporary file removed by the handler; `path` must stay valid until unregistered.
int register_temp_file(const char* path);
void unregister_temp_file(int slot);
// A child process group (its leader's pid) sent SIGTERM by the handler.
void register_child_group(pid_t pgid);
void unregister_child_group(pid_t pgid);

// In a child between fork and exec (async-signal-safe): kInterruptSignals back to their
// default action (an ignored one stays ignored).
void default_interrupt_actions();
// In a forked child that does not exec (process.h run_forked): the default actions, and
// the parent's registries forgotten (its files and children are not the child's to
// remove or stop).
void reset_interrupt_handling_in_child();

}  // namespace rastsim
