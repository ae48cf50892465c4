// The exit codes of phdslam: 0 success, 1 a run or evaluation failed (or a file could not be
// read), 2 a usage error (bad option, experiment file or list; unknown name; conflicting results
// folders), 130 interrupted (Ctrl-C).
#pragma once

namespace phdslam::apps {

inline constexpr int kExitRunFailed = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = 130;

}  // namespace phdslam::apps
