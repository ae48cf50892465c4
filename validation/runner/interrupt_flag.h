// Ctrl-C handling for long Monte Carlo invocations: the first SIGINT sets a flag that the runner
// checks between runs (runs in progress finish and are kept); a second SIGINT terminates the
// process as usual.
#pragma once

#include <atomic>

namespace phdslam::validation {

/// Installs the SIGINT handler for its lifetime and restores the previous one on destruction.
/// Only one may exist at a time (throws std::logic_error otherwise).
class InterruptFlag {
 public:
  InterruptFlag();
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;

  /// The flag the signal handler sets; stays set until destruction.
  [[nodiscard]] const std::atomic<bool>& flag() const;
};

}  // namespace phdslam::validation
