// The arrow-structured joint IPL of PHD-SLAM 2.0b (src/filters/phd2b_density.h) against the
// stacked dense Kalman update it replaces, kept here as the reference computation: the two are
// equal in real arithmetic, so on random problems the means, the pose covariances and the dense
// joint covariances agree to a relative 1e-9, and the iteration counts and stop flags are equal.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/random.h"
#include "src/filters/ipl.h"
#include "src/filters/phd2b_density.h"
#include "src/models/range_bearing_model.h"
#include "src/testing/jacobian_check.h"

namespace phdslam::filters {
namespace {

struct DenseResult {
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;
  int iterations = 0;
  bool cholesky_failed = false;
  bool nis_stopped = false;
};

/// The joint IPL as one stacked Kalman update of the dense (3 + 2M)^2 joint prior per iteration
/// (O(M^3)): the definition the arrow-structured JointIpl must reproduce.
DenseResult DenseJointIpl(const Pose& prior_mean, const Mat3& prior_cov,
                          std::span<const IplPair> pairs, const Mat2& noise_cov,
                          const JointIplOptions& options) {
  const auto num_pairs = static_cast<Eigen::Index>(pairs.size());
  const Eigen::Index n = 3 + 2 * num_pairs;
  const Eigen::Index nz = 2 * num_pairs;
  Eigen::VectorXd x0(n);
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n);
  x0.head<3>() = prior_mean;
  p0.topLeftCorner<3, 3>() = prior_cov;
  for (Eigen::Index p = 0; p < num_pairs; ++p) {
    x0.segment<2>(3 + 2 * p) = pairs[p].landmark_mean;
    p0.block<2, 2>(3 + 2 * p, 3 + 2 * p) = pairs[p].landmark_cov;
  }
  DenseResult lin{x0, p0, 0, false, false};
  if (num_pairs == 0) return lin;
  double nis_limit = std::numeric_limits<double>::infinity();
  if (options.nis_tail_probability > 0.0) {
    nis_limit = ChiSquareUpperQuantileEvenDof(static_cast<int>(nz), options.nis_tail_probability);
  }
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(nz, n);
  Eigen::VectorXd nu(nz);
  for (int l = 1; l <= options.max_iterations; ++l) {
    const Pose lin_pose = lin.mean.head<3>();
    const Vec3 pose_offset = prior_mean - lin_pose;
    for (Eigen::Index p = 0; p < num_pairs; ++p) {
      const Landmark lin_landmark = lin.mean.segment<2>(3 + 2 * p);
      const auto j = models::MeasurementJacobians(lin_pose, lin_landmark);
      h.block<2, 3>(2 * p, 0) = j.hx;
      h.block<2, 2>(2 * p, 3 + 2 * p) = j.hm;
      Vec2 r = pairs[p].z - models::PredictMeasurement(lin_pose, lin_landmark) -
               j.hx * pose_offset - j.hm * (pairs[p].landmark_mean - lin_landmark);
      r(1) = WrapAngle(r(1));
      nu.segment<2>(2 * p) = r;
    }
    const Eigen::MatrixXd pht = p0 * h.transpose();
    Eigen::MatrixXd s = h * pht;
    for (Eigen::Index p = 0; p < num_pairs; ++p) s.block<2, 2>(2 * p, 2 * p) += noise_cov;
    s = (0.5 * (s + s.transpose())).eval();
    const Eigen::LLT<Eigen::MatrixXd> s_llt(s);
    if (s_llt.info() != Eigen::Success) {
      lin.cholesky_failed = true;
      break;
    }
    if (nu.dot(s_llt.solve(nu)) >= nis_limit) {
      lin.nis_stopped = true;
      break;
    }
    const Eigen::MatrixXd gain = s_llt.solve(pht.transpose()).transpose();
    Eigen::VectorXd m = x0 + gain * nu;
    Eigen::MatrixXd cov = p0 - gain * pht.transpose();
    cov = (0.5 * (cov + cov.transpose())).eval();
    if (!LltIsPositiveDefinite(Eigen::LLT<Eigen::MatrixXd>(cov))) {
      lin.cholesky_failed = true;
      break;
    }
    const bool converged =
        l >= 2 && KlDivergence3(lin.mean.head<3>(), lin.cov.topLeftCorner<3, 3>(), m.head<3>(),
                                cov.topLeftCorner<3, 3>()) < options.kl_tolerance;
    lin.mean = std::move(m);
    lin.cov = std::move(cov);
    lin.iterations = l;
    if (converged) break;
  }
  return lin;
}

Mat2 NoiseCov() {
  Mat2 r;
  r << 0.64, 0.0, 0.0, 2.7416e-5;
  return r;
}

/// A random rotation of dimension N: Givens rotations by uniform angles in every coordinate plane
/// (every rotation is such a product; a QR factorisation would cost far more to compile).
template <int N>
Eigen::Matrix<double, N, N> RandomRotation(RandomStream& rng) {
  Eigen::Matrix<double, N, N> q = Eigen::Matrix<double, N, N>::Identity();
  for (int i = 0; i < N; ++i) {
    for (int j = i + 1; j < N; ++j) {
      const double angle = rng.Uniform(-M_PI, M_PI);
      Eigen::Matrix<double, N, N> g = Eigen::Matrix<double, N, N>::Identity();
      g(i, i) = std::cos(angle);
      g(j, j) = std::cos(angle);
      g(i, j) = -std::sin(angle);
      g(j, i) = std::sin(angle);
      q = (q * g).eval();
    }
  }
  return q;
}

/// A random symmetric positive-definite 2x2 or 3x3 with eigenvalues in [low, high].
template <int N>
Eigen::Matrix<double, N, N> RandomSpd(RandomStream& rng, double low, double high) {
  const Eigen::Matrix<double, N, N> q = RandomRotation<N>(rng);
  Eigen::Matrix<double, N, 1> eig;
  for (int i = 0; i < N; ++i) eig(i) = rng.Uniform(low, high);
  return q * eig.asDiagonal() * q.transpose();
}

struct Problem {
  Pose prior_mean;
  Mat3 prior_cov;
  std::vector<IplPair> pairs;
};

/// A pose with a random prior, M landmarks 3-40 m away with random covariances, and their
/// measurements from a pose and landmarks drawn from those priors, with the sensor noise.
Problem RandomProblem(RandomStream& rng, int num_pairs) {
  Problem problem;
  problem.prior_mean = Pose(rng.Uniform(-100, 100), rng.Uniform(-100, 100), rng.Uniform(-3, 3));
  // Heading variances a hundredth of the position ones (rad^2 against m^2), kept positive
  // definite by scaling rows and columns alike.
  const Vec3 scale(1.0, 1.0, 0.1);
  problem.prior_cov = scale.asDiagonal() * RandomSpd<3>(rng, 1e-3, 1.0) * scale.asDiagonal();
  const auto pose_draw = *CholeskyLower(problem.prior_cov);
  const Pose truth =
      problem.prior_mean + pose_draw * Vec3(rng.Normal(), rng.Normal(), rng.Normal());
  const auto noise = *CholeskyLower(NoiseCov());
  for (int p = 0; p < num_pairs; ++p) {
    const double range = rng.Uniform(3.0, 40.0);
    const double bearing = rng.Uniform(-1.5, 1.5);
    const Landmark mean =
        problem.prior_mean.head<2>() + range * Vec2(std::cos(problem.prior_mean(2) + bearing),
                                                    std::sin(problem.prior_mean(2) + bearing));
    const Mat2 cov = RandomSpd<2>(rng, 0.01, 2.0);
    const Landmark true_landmark = mean + *CholeskyLower(cov) * Vec2(rng.Normal(), rng.Normal());
    Measurement z =
        models::PredictMeasurement(truth, true_landmark) + noise * Vec2(rng.Normal(), rng.Normal());
    z(1) = WrapAngle(z(1));
    problem.pairs.push_back({mean, cov, z});
  }
  return problem;
}

double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / a.cwiseAbs().maxCoeff();
}

void ExpectAgreement(const Problem& problem, const JointIplOptions& options, int trial) {
  const DenseResult dense =
      DenseJointIpl(problem.prior_mean, problem.prior_cov, problem.pairs, NoiseCov(), options);
  const JointIplResult arrow =
      JointIpl(problem.prior_mean, problem.prior_cov, problem.pairs, NoiseCov(), options);
  SCOPED_TRACE(::testing::Message() << "trial " << trial << ", M = " << problem.pairs.size());
  EXPECT_EQ(arrow.iterations, dense.iterations);
  EXPECT_EQ(arrow.cholesky_failed, dense.cholesky_failed);
  EXPECT_EQ(arrow.nis_stopped, dense.nis_stopped);
  ASSERT_EQ(arrow.mean.size(), dense.mean.size());
  // The mean relative to its own scale (the pose and landmark coordinates are ~100 m), and the
  // covariances relative to their largest entry.
  EXPECT_LT(RelativeDifference(dense.mean, arrow.mean), 1e-9);
  const Eigen::MatrixXd dense_pose = dense.cov.topLeftCorner<3, 3>();
  const Eigen::MatrixXd arrow_pose = arrow.pose_cov();
  EXPECT_LT(RelativeDifference(dense_pose, arrow_pose), 1e-9);
  EXPECT_LT(RelativeDifference(dense.cov, arrow.JointCovariance()), 1e-9);
  // The increments over the prior agree too (a stricter test than the absolute mean).
  Eigen::VectorXd prior(dense.mean.size());
  prior.head<3>() = problem.prior_mean;
  for (std::size_t p = 0; p < problem.pairs.size(); ++p) {
    prior.segment<2>(3 + 2 * static_cast<Eigen::Index>(p)) = problem.pairs[p].landmark_mean;
  }
  const Eigen::VectorXd dense_step = dense.mean - prior;
  const Eigen::VectorXd arrow_step = arrow.mean - prior;
  if (dense_step.cwiseAbs().maxCoeff() > 0.0) {
    EXPECT_LT(RelativeDifference(dense_step, arrow_step), 1e-9);
  }
  testing::ExpectSymmetricPositiveDefinite(arrow.JointCovariance());
}

TEST(JointIplArrow, AgreesWithTheDenseStackedUpdateOnRandomProblems) {
  RandomStream rng(DeriveSeed(HashName("joint-ipl-arrow-test"), 1));
  int trial = 0;
  for (const int m : {1, 2, 3, 5, 10, 20, 40}) {
    for (int repeat = 0; repeat < 10; ++repeat, ++trial) {
      const Problem problem = RandomProblem(rng, m);
      // Fixed five iterations (the convergence test never fires), and the filter's settings.
      ExpectAgreement(problem, {5, 0.0}, trial);
      ExpectAgreement(problem, {5, 1e-3}, trial);
      JointIplOptions guarded{5, 1e-3};
      guarded.nis_tail_probability = 1e-6;
      ExpectAgreement(problem, guarded, trial);
    }
  }
}

TEST(JointIplArrow, AgreesWhenTheGuardStopsAndWhenTheLandmarksAreNearlyKnown) {
  RandomStream rng(DeriveSeed(HashName("joint-ipl-arrow-test"), 2));
  JointIplOptions guarded{5, 1e-3};
  guarded.nis_tail_probability = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    Problem problem = RandomProblem(rng, 6);
    problem.pairs[2].z(0) += 30.0;  // an inconsistent association: the guard stops iteration 1
    const DenseResult dense =
        DenseJointIpl(problem.prior_mean, problem.prior_cov, problem.pairs, NoiseCov(), guarded);
    const JointIplResult arrow =
        JointIpl(problem.prior_mean, problem.prior_cov, problem.pairs, NoiseCov(), guarded);
    EXPECT_TRUE(dense.nis_stopped);
    EXPECT_TRUE(arrow.nis_stopped);
    EXPECT_EQ(arrow.iterations, dense.iterations);
    EXPECT_TRUE(arrow.mean == dense.mean)  // both keep the prior
        << "arrow: " << arrow.mean.transpose() << "\ndense: " << dense.mean.transpose();
    // Nearly known landmarks (covariance 1e-8 m^2): the joint posterior is ill-conditioned in
    // the landmark blocks but both computations still agree.
    Problem tight = RandomProblem(rng, 8);
    for (IplPair& pair : tight.pairs) pair.landmark_cov *= 1e-8;
    ExpectAgreement(tight, {5, 1e-3}, 100 + trial);
  }
}

}  // namespace
}  // namespace phdslam::filters
