// GOSPA (alpha = 2; Rahmathullah, Garcia-Fernandez & Svensson 2017) and OSPA (Schuhmacher, Vo &
// Vo 2008) between two finite point sets, with their decompositions.
#pragma once

#include <utility>
#include <vector>

#include "src/core/types.h"

namespace phdslam::validation {

struct GospaResult {
  double gospa = 0.0;                      ///< (localisation + missed + false_)^(1/p)
  double localisation = 0.0;               ///< sum over assigned pairs of d^p (p-th power units)
  double missed = 0.0;                     ///< (c^p / 2) * n_missed
  double false_ = 0.0;                     ///< (c^p / 2) * n_false (JSON key "false")
  int n_missed = 0;                        ///< truth points without an estimate closer than c
  int n_false = 0;                         ///< estimates without a truth point closer than c
  std::vector<std::pair<int, int>> pairs;  ///< (truth index, estimate index) with d < c, by truth
};

/// GOSPA with alpha = 2 and the Euclidean base distance d. The optimal assignment is solved
/// exactly on min(d, c)^p (not on d), so a pair with d >= c is never preferred to leaving both
/// points unassigned; such pairs count as one missed and one false point. Either set may be empty
/// (an empty estimate gives gospa = (|truth| c^p / 2)^(1/p), with the p-th root).
/// Throws std::invalid_argument unless c > 0, p >= 1 (both finite) and every point is finite.
GospaResult Gospa(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate, double c,
                  double p);

struct OspaResult {
  double ospa = 0.0;          ///< ((sum min(d, c)^p + c^p (n - m)) / n)^(1/p), n = max set size
  double localisation = 0.0;  ///< (sum min(d, c)^p / n)^(1/p)
  double cardinality = 0.0;   ///< (c^p (n - m) / n)^(1/p); ospa^p = localisation^p + cardinality^p
};

/// OSPA of order p with cut-off c, assignment solved exactly on min(d, c)^p. Both sets empty gives
/// zero; one empty gives c. Same input checks as Gospa.
OspaResult Ospa(const std::vector<Vec2>& truth, const std::vector<Vec2>& estimate, double c,
                double p);

}  // namespace phdslam::validation
