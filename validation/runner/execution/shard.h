// A shard of a Monte Carlo experiment: `--shard i/n` runs the jobs whose index in the
// experiment's deterministic job order is i - 1 modulo n, so n machines (or a job array) split one
// experiment and `phdslam merge` joins their folders.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace phdslam::validation {

struct Shard {
  int index = 1;  ///< 1-based, 1 <= index <= count
  int count = 1;

  /// True when job `job_index` (0-based, in the experiment's job order) belongs to this shard.
  [[nodiscard]] bool Contains(std::size_t job_index) const {
    return job_index % static_cast<std::size_t>(count) == static_cast<std::size_t>(index - 1);
  }
  [[nodiscard]] bool IsWhole() const { return count == 1; }
  /// "i/n"
  [[nodiscard]] std::string ToString() const {
    return std::to_string(index) + "/" + std::to_string(count);
  }
};

/// Parses "i/n" with 1 <= i <= n (decimal integers, n <= 1000000). Throws std::invalid_argument
/// naming the text otherwise.
Shard ParseShard(std::string_view text);

}  // namespace phdslam::validation
