// Labelled track entries of the delta-GLMB map (docs/algorithms/glmb-slam.md section 3.1): an entry
// is the immutable density of one label under one association history, shared by every hypothesis
// (and every resampled particle copy) that holds it.
#pragma once

#include <compare>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "src/core/types.h"

namespace phdslam::glmb {

/// l = (k_b, j): the step at which the birth Bernoulli is first offered to the update and the
/// index of its generating measurement in the previous scan.
struct Label {
  int birth_step = 0;
  int index = 0;
  bool operator==(const Label&) const = default;
  /// Lexicographic, birth step first, as a defaulted <=> orders (written out because clang-tidy
  /// 14 reports the comparison with 0 that the defaulted one synthesises as modernize-use-nullptr).
  std::strong_ordering operator<=>(const Label& other) const {
    return std::tie(birth_step, index) <=> std::tie(other.birth_step, other.index);
  }
};

/// One Gaussian of an entry's density (entries of the delta-GLMB filters have exactly one; LMB
/// tracks carry a mixture).
struct TrackComponent {
  double log_weight = 0.0;  ///< normalised over the entry
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Identity();
};

/// An immutable entry. `id` is unique among the entries of one particle's lineage and orders the
/// entries of a hypothesis; equal id vectors mean equal hypotheses (docs/algorithms/glmb-slam.md
/// section 4.4).
struct Track {
  std::uint64_t id = 0;
  Label label;
  std::vector<TrackComponent> gm;

  /// The heaviest component (first on ties): its mean is the entry's point for the FOV test and
  /// the estimate.
  [[nodiscard]] const TrackComponent& Heaviest() const {
    std::size_t best = 0;
    for (std::size_t c = 1; c < gm.size(); ++c) {
      if (gm[c].log_weight > gm[best].log_weight) best = c;
    }
    return gm[best];
  }
};

using TrackPtr = std::shared_ptr<const Track>;

/// A single-Gaussian entry.
inline TrackPtr MakeTrack(std::uint64_t id, Label label, const Landmark& mean, const Mat2& cov) {
  return std::make_shared<const Track>(Track{id, label, {TrackComponent{0.0, mean, cov}}});
}

}  // namespace phdslam::glmb
