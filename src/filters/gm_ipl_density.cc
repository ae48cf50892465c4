#include "src/filters/gm_ipl_density.h"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory_resource>
#include <numbers>
#include <vector>

#include "src/assignment/block_murty.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/filters/ipl.h"
#include "src/models/range_bearing_model.h"
#include "src/models/sensor_model.h"

namespace phdslam::filters {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Stack bytes for the scratch lists of one association-cost or proposal build.
constexpr std::size_t kScratchArenaBytes = std::size_t{8} * 1024;

}  // namespace

AssociationCosts BuildAssociationCosts(const ProposalInput& input, const PhdSlamParams& params) {
  const std::span<const phd::GaussianComponent> active = input.landmarks;
  const int m = static_cast<int>(active.size());
  const int nz = static_cast<int>(input.measurements.size());
  const double log_clutter = std::log(input.sensor->ClutterIntensity());
  const double log_two_pi = std::log(2.0 * std::numbers::pi);
  AssociationCosts c;
  c.pd.resize(m);
  c.miss.resize(m);
  // The gated log gains, row by row: (index into c.rows, measurement, gain).
  struct Gated {
    int row;
    int col;
    double gain;
  };
  std::array<std::byte, kScratchArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  std::pmr::vector<Gated> gated(&arena);
  gated.reserve(2 * static_cast<std::size_t>(m));
  c.rows.reserve(m);
  c.row_prediction.reserve(m);
  c.cols.reserve(nz);
  std::pmr::vector<int> col_of(nz, -1, &arena);
  const models::FovView fov(*input.sensor, input.predicted_mean);
  models::LogDetectionTerms log_pd;
  for (int i = 0; i < m; ++i) {
    const phd::GaussianComponent& comp = active[i];
    const double pd = fov.DetectionProbability(comp.mean);
    log_pd.Set(pd);
    c.pd[i] = pd;
    c.miss[i] = log_pd.log_miss() + comp.log_weight;
    if (pd <= 0.0) continue;
    const models::PredictionWithJacobians prediction =
        models::PredictWithJacobians(input.predicted_mean, comp.mean);
    const auto& [z_hat, j] = prediction;
    Mat2 s = j.hx * input.predicted_cov * j.hx.transpose() + j.hm * comp.cov * j.hm.transpose() +
             input.sensor->noise_cov;
    Symmetrize(s);
    // The log-normaliser, formed when the first measurement passes the gate.
    double base = 0.0;
    bool have_base = false;
    const Mat2 s_inv = s.inverse();
    const int row = static_cast<int>(c.rows.size());
    const double range_window = FirstCoordinateGateHalfWidth(s, params.map.gate_threshold);
    for (int jz = 0; jz < nz; ++jz) {
      if (std::abs(input.measurements[jz](0) - z_hat(0)) > range_window) continue;
      Vec2 nu = input.measurements[jz] - z_hat;
      nu(1) = WrapAngle(nu(1));
      const double d2 = nu.dot(s_inv * nu);
      if (d2 < params.map.gate_threshold) {
        if (!have_base) {
          base = log_pd.log_pd() + comp.log_weight - log_clutter - log_two_pi -
                 0.5 * std::log(s.determinant());
          have_base = true;
        }
        gated.push_back({row, jz, base - 0.5 * d2});
        col_of[jz] = 0;
      }
    }
    if (!gated.empty() && gated.back().row == row) {
      c.rows.push_back(i);
      c.row_prediction.push_back(prediction);
    }
  }
  for (int jz = 0; jz < nz; ++jz) {
    if (col_of[jz] == 0) {
      col_of[jz] = static_cast<int>(c.cols.size());
      c.cols.push_back(jz);
    }
  }
  const int r = static_cast<int>(c.rows.size());
  const int k = static_cast<int>(c.cols.size());
  c.cost = Eigen::MatrixXd::Constant(r, k + r, kInf);
  for (const Gated& g : gated) {
    if (g.gain > -kInf) c.cost(g.row, col_of[g.col]) = -g.gain;
  }
  for (int a = 0; a < r; ++a) c.cost(a, k + a) = -c.miss[c.rows[a]];
  return c;
}

ProposalOutput GmIplDensity::Build(const ProposalInput& input) const {
  const std::span<const phd::GaussianComponent> active = input.landmarks;
  if (params_.max_hypotheses <= 0 || active.empty() || input.measurements.empty()) {
    // Nothing to associate with: every measurement is clutter or a new landmark.
    return PriorProposal(input);
  }
  const AssociationCosts costs = BuildAssociationCosts(input, params_);
  const int r = static_cast<int>(costs.rows.size());
  const int k = static_cast<int>(costs.cols.size());
  const double log_clutter = std::log(input.sensor->ClutterIntensity());

  double all_miss = 0.0;
  for (double v : costs.miss) all_miss += v;

  std::vector<assignment::Assignment> hypotheses;
  if (r == 0) {
    hypotheses.push_back({{}, 0.0});
  } else {
    hypotheses =
        assignment::BlockMurtyKBest(costs.cost, params_.max_hypotheses, params_.murty_max_cost_gap);
  }

  ProposalOutput out;
  out.mixture.Reserve(hypotheses.size() + 1);
  out.best_association.assign(input.measurements.size(), -1);
  std::array<std::byte, kScratchArenaBytes> arena_bytes;  // uninitialised: the arena writes it
  std::pmr::monotonic_buffer_resource arena(arena_bytes.data(), arena_bytes.size());
  std::pmr::vector<IplPair> pairs(&arena);
  std::pmr::vector<int> detected_rows(&arena);
  pairs.reserve(r);
  detected_rows.reserve(r);
  const IplOptions ipl_options{params_.ipl_iterations, params_.ipl_kl_tolerance};
  models::LogDetectionTerms log_pd;
  for (std::size_t h = 0; h < hypotheses.size(); ++h) {
    const auto& row_to_col = hypotheses[h].row_to_col;
    pairs.clear();
    detected_rows.clear();
    // Rows are in ascending active-list order, so the IPL processes detections in that order.
    for (int a = 0; a < r; ++a) {
      const int col = row_to_col[a];
      if (col < k) {
        const phd::GaussianComponent& comp = active[costs.rows[a]];
        pairs.push_back(
            {comp.mean, comp.cov, input.measurements[costs.cols[col]], &costs.row_prediction[a]});
        detected_rows.push_back(a);
      }
    }
    const IplResult ipl = PartitionedIpl(input.predicted_mean, input.predicted_cov, pairs,
                                         input.sensor->noise_cov, ipl_options);
    // Component log-weight (44): detections evaluated at the IPL posterior, misses as priors.
    double log_kappa = all_miss;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const int i = costs.rows[detected_rows[p]];
      const phd::GaussianComponent& comp = active[i];
      log_pd.Set(costs.pd[i]);
      const auto [z_hat, j] = models::PredictWithJacobians(ipl.mean, comp.mean);
      Mat2 s = j.hx * ipl.cov * j.hx.transpose() + j.hm * comp.cov * j.hm.transpose() +
               input.sensor->noise_cov;
      Symmetrize(s);
      Vec2 nu = pairs[p].z - z_hat;
      nu(1) = WrapAngle(nu(1));
      log_kappa += -costs.miss[i] + log_pd.log_pd() + comp.log_weight - log_clutter +
                   EvalGaussian2(nu, s).log_pdf;
    }
    out.mixture.Add(log_kappa, ipl.mean, ipl.cov);
    if (h == 0) {
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        out.best_association[costs.cols[row_to_col[detected_rows[p]]]] =
            costs.rows[detected_rows[p]];
      }
    }
  }
  if (params_.all_clutter_component) {
    out.mixture.Add(all_miss, input.predicted_mean, input.predicted_cov);
  }
  return out;
}

}  // namespace phdslam::filters
