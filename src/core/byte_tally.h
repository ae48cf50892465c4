// Tally of heap bytes held by data structures that may share storage: each block is counted
// once, however many owners point to it (e.g. map parts shared between particles).
#pragma once

#include <cstddef>
#include <unordered_set>
#include <vector>

namespace phdslam {

class ByteTally {
 public:
  /// Counts `bytes` for `block` unless that block was counted before; null blocks count nothing.
  void Add(const void* block, std::size_t bytes) {
    if (block == nullptr || !seen_.insert(block).second) return;
    bytes_ += bytes;
  }
  /// The heap buffer of a vector (its capacity, not its size).
  template <class T>
  void AddVector(const std::vector<T>& v) {
    Add(v.data(), v.capacity() * sizeof(T));
  }
  [[nodiscard]] std::size_t bytes() const { return bytes_; }

 private:
  std::unordered_set<const void*> seen_;
  std::size_t bytes_ = 0;
};

}  // namespace phdslam
