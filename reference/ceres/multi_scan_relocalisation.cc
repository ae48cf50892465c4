#include "reference/ceres/multi_scan_relocalisation.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reference/ceres/landmark_association.h"
#include "src/core/angles.h"

namespace phdslam::reference {
namespace {

Eigen::Rotation2Dd Rotation(const RigidCorrection& c) { return Eigen::Rotation2Dd(c.rotation); }

Vec2 Apply(const RigidCorrection& c, const Vec2& p) { return Rotation(c) * p + c.translation; }

/// The correction that maps the segment (pa, pb) onto (ma, mb): rotation of the directions,
/// translation of the midpoints.
RigidCorrection FromPairs(const Vec2& pa, const Vec2& pb, const Vec2& ma, const Vec2& mb) {
  const Vec2 dp = pb - pa;
  const Vec2 dm = mb - ma;
  RigidCorrection c;
  c.rotation = WrapAngle(std::atan2(dm.y(), dm.x()) - std::atan2(dp.y(), dp.x()));
  c.translation = 0.5 * (ma + mb) - Rotation(c) * (0.5 * (pa + pb));
  return c;
}

/// Each point's nearest landmark within the inlier distance after `c` (kUnassociated if none).
std::vector<int> Assign(const RigidCorrection& c, const std::vector<Landmark>& points,
                        const std::vector<Landmark>& map, double inlier_distance, int* inliers) {
  std::vector<int> out(points.size(), kUnassociated);
  *inliers = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Vec2 q = Apply(c, points[j]);
    double best = inlier_distance * inlier_distance;
    for (std::size_t i = 0; i < map.size(); ++i) {
      const double d2 = (map[i] - q).squaredNorm();
      if (d2 < best) {
        best = d2;
        out[j] = static_cast<int>(i);
      }
    }
    if (out[j] != kUnassociated) ++*inliers;
  }
  return out;
}

/// Whether two assignments disagree: some point is an inlier of both, to different landmarks.
bool Rivals(const std::vector<int>& a, const std::vector<int>& b) {
  for (std::size_t j = 0; j < a.size(); ++j) {
    if (a[j] != kUnassociated && b[j] != kUnassociated && a[j] != b[j]) return true;
  }
  return false;
}

/// Whether the newest pose corrected by `c` lies within the gate of the dead-reckoned one.
bool InPoseGate(const RigidCorrection& c, const Pose& x, const Eigen::LDLT<Mat3>& cov_ldlt,
                double gate, double* mahalanobis2) {
  const Pose y = ApplyCorrection(c, x);
  const Vec3 d(y(0) - x(0), y(1) - x(1), WrapAngle(c.rotation));
  const double d2 = d.dot(cov_ldlt.solve(d));
  *mahalanobis2 = d2;
  return std::isfinite(d2) && d2 < gate;
}

/// Least-squares rigid correction (2-D Procrustes) of the inlier points onto their landmarks.
RigidCorrection Refine(const std::vector<Landmark>& points, const std::vector<Landmark>& map,
                       const std::vector<int>& assignment) {
  Vec2 cp = Vec2::Zero();
  Vec2 cm = Vec2::Zero();
  double n = 0.0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (assignment[j] == kUnassociated) continue;
    cp += points[j];
    cm += map[static_cast<std::size_t>(assignment[j])];
    n += 1.0;
  }
  cp /= n;
  cm /= n;
  double dot = 0.0;
  double cross = 0.0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (assignment[j] == kUnassociated) continue;
    const Vec2 p = points[j] - cp;
    const Vec2 m = map[static_cast<std::size_t>(assignment[j])] - cm;
    dot += p.dot(m);
    cross += p.x() * m.y() - p.y() * m.x();
  }
  RigidCorrection c;
  c.rotation = std::atan2(cross, dot);
  c.translation = cm - Rotation(c) * cp;
  return c;
}

double Baseline(const std::vector<Landmark>& points, const std::vector<int>& assignment) {
  double out = 0.0;
  for (std::size_t a = 0; a < points.size(); ++a) {
    if (assignment[a] == kUnassociated) continue;
    for (std::size_t b = a + 1; b < points.size(); ++b) {
      if (assignment[b] != kUnassociated) out = std::max(out, (points[a] - points[b]).norm());
    }
  }
  return out;
}

struct Hypothesis {
  RigidCorrection correction;
  std::vector<int> assignment;
  int inliers = 0;
  double score = 0.0;  ///< inliers - prior_weight * d2 / 2
};

}  // namespace

Pose ApplyCorrection(const RigidCorrection& c, const Pose& x) {
  const Vec2 p = Apply(c, x.head<2>());
  return {p.x(), p.y(), x(2) + c.rotation};
}

RelocalisationMatch MatchPointsToMap(const std::vector<Landmark>& points,
                                     const std::vector<Landmark>& map, const Pose& newest,
                                     const Mat3& newest_cov, const RelocalisationOptions& options) {
  if (!(options.inlier_distance > 0.0)) {
    throw std::invalid_argument("RelocalisationOptions.inlier_distance: expected > 0");
  }
  if (options.margin < 1)
    throw std::invalid_argument("RelocalisationOptions.margin: expected >= 1");
  if (!(options.prior_weight >= 0.0)) {
    throw std::invalid_argument("RelocalisationOptions.prior_weight: expected >= 0");
  }
  if (!(options.pose_gate_chi2 > 0.0)) {
    throw std::invalid_argument("RelocalisationOptions.pose_gate_chi2: expected > 0");
  }
  const double tol = options.inlier_distance;
  const Eigen::LDLT<Mat3> ldlt(newest_cov);
  std::vector<Hypothesis> kept;  // the best of each group of compatible hypotheses
  for (std::size_t a = 0; a < points.size(); ++a) {
    for (std::size_t b = a + 1; b < points.size(); ++b) {
      const double dp = (points[b] - points[a]).norm();
      if (dp < 2.0 * tol) continue;
      for (std::size_t i = 0; i < map.size(); ++i) {
        for (std::size_t k = 0; k < map.size(); ++k) {
          if (i == k || std::abs((map[k] - map[i]).norm() - dp) >= tol) continue;
          Hypothesis h;
          h.correction = FromPairs(points[a], points[b], map[i], map[k]);
          double d2 = 0.0;
          if (!InPoseGate(h.correction, newest, ldlt, options.pose_gate_chi2, &d2)) continue;
          h.assignment = Assign(h.correction, points, map, tol, &h.inliers);
          h.score = h.inliers - options.prior_weight * 0.5 * d2;
          auto same = std::find_if(kept.begin(), kept.end(), [&](const Hypothesis& g) {
            return !Rivals(g.assignment, h.assignment);
          });
          if (same == kept.end()) {
            kept.push_back(std::move(h));
          } else if (h.score > same->score) {
            *same = std::move(h);
          }
        }
      }
    }
  }
  RelocalisationMatch out;
  out.landmark.assign(points.size(), kUnassociated);
  if (kept.empty()) return out;
  std::sort(kept.begin(), kept.end(),
            [](const Hypothesis& x, const Hypothesis& y) { return x.score > y.score; });
  const Hypothesis& best = kept.front();
  out.best_inliers = best.inliers;
  double rival_score = -1e300;
  for (std::size_t n = 1; n < kept.size(); ++n) {
    if (Rivals(best.assignment, kept[n].assignment) && kept[n].score > rival_score) {
      rival_score = kept[n].score;
      out.rival_inliers = kept[n].inliers;
    }
  }
  if (best.inliers < 3) return out;
  if (best.score - rival_score < options.margin) {
    out.ambiguous = true;
    return out;
  }
  out.found = true;
  out.correction = Refine(points, map, best.assignment);
  int inliers = 0;
  out.landmark = Assign(out.correction, points, map, tol, &inliers);
  if (Rivals(out.landmark, best.assignment) || inliers < best.inliers) {
    out.correction = best.correction;  // the refinement moved points off: keep the pair's
    out.landmark = best.assignment;
  }
  out.baseline = Baseline(points, out.landmark);
  return out;
}

}  // namespace phdslam::reference
