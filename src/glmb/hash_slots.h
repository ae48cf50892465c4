// The look-up table shared by the joint update's sets of records (a chain's distinct samples, an
// update's children): record indices by 64-bit hash, open addressing with linear probing, a power
// of two of slots at most half full. The records and their hashes live with the caller, which
// alone can compare two records.
#pragma once

#include <cstdint>
#include <vector>

namespace phdslam::glmb {

class HashSlots {
 public:
  /// Slots in `storage` (reused by a caller that builds many sets), emptied to 16.
  explicit HashSlots(std::vector<int>& storage) : slots_(storage) { slots_.assign(16, -1); }

  /// The record k with this hash for which same(k) holds, or -1.
  template <class Same>
  [[nodiscard]] int Find(std::uint64_t hash, Same&& same) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = hash & mask; slots_[i] >= 0; i = (i + 1) & mask) {
      if (same(slots_[i])) return slots_[i];
    }
    return -1;
  }

  /// Adds record k (records 0..k-1 added before), doubling the slots when over half full;
  /// hash_of(e) is record e's hash.
  template <class HashOf>
  void Insert(int k, HashOf&& hash_of) {
    if (2 * (static_cast<std::size_t>(k) + 1) > slots_.size()) {
      slots_.assign(2 * slots_.size(), -1);
      for (int e = 0; e < k; ++e) Place(e, hash_of(e));
    }
    Place(k, hash_of(k));
  }

 private:
  void Place(int k, std::uint64_t hash) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = hash & mask;
    while (slots_[i] >= 0) i = (i + 1) & mask;
    slots_[i] = k;
  }

  std::vector<int>& slots_;
};

}  // namespace phdslam::glmb
