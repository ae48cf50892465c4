// Ctrl-C, SIGTERM and SIGHUP handling for long Monte Carlo invocations: the first SIGINT, SIGTERM
// or SIGHUP (a closed terminal) sets a
// flag that the runner checks between runs (runs in progress finish and are kept, the summary is
// written); a second one terminates the process as usual.
#pragma once

#include <signal.h>

#include <atomic>

namespace phdslam::validation {

/// Installs the SIGINT handler for its lifetime and restores the previous one on destruction.
/// Create one at a time (the program's main does).
class InterruptFlag {
 public:
  InterruptFlag();
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;

  /// The flag the signal handler sets; stays set until destruction.
  [[nodiscard]] const std::atomic<bool>& flag() const;

 private:
  struct sigaction previous_action_ {};
  struct sigaction previous_term_action_ {};
  struct sigaction previous_hangup_action_ {};
};

}  // namespace phdslam::validation
