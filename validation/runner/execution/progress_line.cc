#include "validation/runner/execution/progress_line.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace phdslam::validation {

ProgressLine::ProgressLine(std::size_t runs, bool enabled)
    : runs_(runs),
      draw_(enabled && runs > 0 && isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {
  if (draw_) thread_ = std::thread([this] { Loop(); });
}

ProgressLine::~ProgressLine() { Finish(); }

void ProgressLine::RunStarted(std::size_t steps) {
  steps_started_ += steps;
  ++runs_started_;
}

void ProgressLine::StepsDone(std::size_t steps) { steps_done_ += steps; }

void ProgressLine::RunFinished(bool failed) {
  ++runs_finished_;
  if (failed) ++runs_failed_;
}

void ProgressLine::Message(const std::string& text) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (draw_ && !stop_) std::fputs("\r\033[K", stderr);
  std::fputs((text + "\n").c_str(), stderr);
  if (draw_ && !stop_) std::fputs(Render().c_str(), stderr);
  std::fflush(stderr);
}

void ProgressLine::Finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) return;
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (draw_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

std::string ProgressLine::FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const auto total = static_cast<long long>(std::llround(seconds));
  char buffer[48];
  if (total >= 3600) {
    std::snprintf(buffer, sizeof(buffer), "%lldh%02lldm", total / 3600, (total % 3600) / 60);
  } else if (total >= 60) {
    std::snprintf(buffer, sizeof(buffer), "%lldm%02llds", total / 60, total % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%llds", total);
  }
  return buffer;
}

std::string ProgressLine::Render() const {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t started = runs_started_.load();
  const std::size_t finished = runs_finished_.load();
  // Total work estimated from the scenarios built so far (all runs of a scenario usually have
  // the same length).
  double fraction = 0.0;
  if (started > 0) {
    const double steps_per_run =
        static_cast<double>(steps_started_.load()) / static_cast<double>(started);
    const double total = steps_per_run * static_cast<double>(runs_);
    if (total > 0.0) fraction = std::min(1.0, static_cast<double>(steps_done_.load()) / total);
  }
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : NAN;
  const std::size_t failed = runs_failed_.load();
  const std::string failures = failed > 0 ? ", " + std::to_string(failed) + " failed" : "";
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "runs %zu/%zu done%s, %.1f%%, elapsed %s, ETA %s", finished,
                runs_, failures.c_str(), 100.0 * fraction, FormatDuration(elapsed).c_str(),
                FormatDuration(eta).c_str());
  return buffer;
}

void ProgressLine::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    std::fputs(("\r\033[K" + Render()).c_str(), stderr);
    std::fflush(stderr);
    wake_.wait_for(lock, std::chrono::milliseconds(500), [this] { return stop_; });
  }
}

}  // namespace phdslam::validation
