// One updating progress line with an ETA on stderr, drawn only when stderr is a terminal.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace phdslam::validation {

class ProgressLine {
 public:
  /// `runs` is the number of runs to compute. When `enabled` is false, or stderr is not a
  /// terminal, nothing is drawn (Message still prints).
  ProgressLine(std::size_t runs, bool enabled);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// A run has built its scenario of `steps` steps.
  void RunStarted(std::size_t steps);
  void StepsDone(std::size_t steps);
  void RunFinished(bool failed);
  /// Prints a whole line on stderr without garbling the progress line.
  void Message(const std::string& text);
  /// Stops redrawing and clears the line.
  void Finish();

  /// "1h02m", "3m04s", "12s".
  static std::string FormatDuration(double seconds);

 private:
  std::string Render() const;
  void Loop();

  const std::size_t runs_;
  const bool draw_;
  const std::chrono::steady_clock::time_point start_;
  std::atomic<std::size_t> runs_started_{0};
  std::atomic<std::size_t> runs_finished_{0};
  std::atomic<std::size_t> runs_failed_{0};
  std::atomic<std::uint64_t> steps_started_{0};
  std::atomic<std::uint64_t> steps_done_{0};
  std::mutex mutex_;  // guards stderr output and stop_
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace phdslam::validation
