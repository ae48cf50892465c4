// An exclusive lock on a results folder, so that two phdslam processes never write one folder at
// once (they would overwrite each other's temporary files).
#pragma once

#include <filesystem>

namespace phdslam::validation {

inline constexpr const char* kLockFile = "phdslam.lock";

/// Holds an advisory lock (flock) on <folder>/phdslam.lock for its lifetime and removes the file
/// on release; the folder is created when missing. The lock ends with the process, so a killed
/// run leaves at most an unlocked file, never a stale lock.
class ResultsLock {
 public:
  /// Throws std::runtime_error naming the folder when another process holds the lock or the lock
  /// file cannot be created.
  explicit ResultsLock(const std::filesystem::path& folder);
  ~ResultsLock();
  ResultsLock(const ResultsLock&) = delete;
  ResultsLock& operator=(const ResultsLock&) = delete;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace phdslam::validation
