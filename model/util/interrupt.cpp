// SPDX-License-Identifier: Apache-2.0
#include "util/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace rastsim {

namespace {

// Temporary files and children alive at once: a few outputs of one run, a sweep's jobs.
constexpr int kSlots = 256;

static_assert(std::atomic<const char*>::is_always_lock_free && std::atomic<pid_t>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

std::atomic<const char*> temp_files[kSlots];
std::atomic<pid_t> child_groups[kSlots];
std::atomic<int> scopes{0};
volatile std::sig_atomic_t received = 0;

void stop_children() {
  for (auto& g : child_groups)
    if (const pid_t p = g.load(); p > 0) kill(-p, SIGTERM);
}

void remove_temp_files() {
  for (auto& f : temp_files)
    if (const char* p = f.load()) unlink(p);
}

void on_signal(int sig) {
  const bool again = received != 0;
  received = sig;
  stop_children();
  if (scopes.load() > 0 && !again) return;  // the code unwinds (interrupt.h)
  remove_temp_files();
  signal(sig, SIG_DFL);
  raise(sig);  // delivered when the handler returns: the process ends by the signal
}

template <typename T>
int claim(std::atomic<T>* table, T value) {
  for (int k = 0; k < kSlots; ++k) {
    T empty{};
    if (table[k].compare_exchange_strong(empty, value)) return k;
  }
  return -1;
}

}  // namespace

void install_interrupt_handler() {
  for (int sig : kInterruptSignals) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // a wait for a child returns when the child, sent SIGTERM, ends
    sigaction(sig, &sa, nullptr);
  }
}

int interrupt_signal() { return received; }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(signal);
  }
}

void throw_if_interrupted() {
  if (const int sig = interrupt_signal()) throw Interrupted(sig, "interrupted by " + signal_name(sig));
}

InterruptScope::InterruptScope() { ++scopes; }
InterruptScope::~InterruptScope() { --scopes; }

int register_temp_file(const char* path) { return claim(temp_files, path); }
void unregister_temp_file(int slot) {
  if (slot >= 0) temp_files[slot].store(nullptr);
}

void register_child_group(pid_t pgid) { claim(child_groups, pgid); }
void unregister_child_group(pid_t pgid) {
  for (auto& g : child_groups) {
    pid_t p = pgid;
    g.compare_exchange_strong(p, 0);
  }
}

void default_interrupt_actions() {
  for (int sig : kInterruptSignals) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler != SIG_IGN) signal(sig, SIG_DFL);
  }
}

void reset_interrupt_handling_in_child() {
  default_interrupt_actions();
  for (auto& f : temp_files) f.store(nullptr);
  for (auto& g : child_groups) g.store(0);
  received = 0;
  scopes.store(0);
}

}  // namespace rastsim
