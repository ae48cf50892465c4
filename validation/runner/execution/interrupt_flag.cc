#include "validation/runner/execution/interrupt_flag.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace phdslam::validation {
namespace {

// The one piece of process-wide state: a signal handler can reach nothing else.
std::atomic<bool> interrupted{false};

static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT flag must be lock-free");

extern "C" void OnSigint(int) {
  interrupted.store(true);
  constexpr char kMessage[] =
      "\nphdslam: interrupted; finishing the runs in progress (Ctrl-C, SIGTERM or SIGHUP again "
      "to abort)\n";
  // write(2) is async-signal-safe; a failed write is of no consequence here.
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kMessage, sizeof(kMessage) - 1);
}

}  // namespace

InterruptFlag::InterruptFlag() {
  interrupted.store(false);
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = OnSigint;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: after the first SIGINT the default action is back, so a second one terminates.
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, &previous_action_);
  // SIGTERM (sent by batch schedulers and container runtimes) stops the same orderly way.
  sigaction(SIGTERM, &action, &previous_term_action_);
  // SIGHUP (the terminal or ssh session closed) too: its default would end the run without its
  // summary.csv.
  sigaction(SIGHUP, &action, &previous_hangup_action_);
}

InterruptFlag::~InterruptFlag() {
  sigaction(SIGINT, &previous_action_, nullptr);
  sigaction(SIGTERM, &previous_term_action_, nullptr);
  sigaction(SIGHUP, &previous_hangup_action_, nullptr);
}

const std::atomic<bool>& InterruptFlag::flag() const { return interrupted; }

}  // namespace phdslam::validation
