// closest_rotation against the defining property and against JacobiSVD, on the kinds of
// matrices the local step meets: near-rotations, stretches, inverted and flattened tets.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <vector>

#include "core/rotation/polar.h"

using namespace slim;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

struct Rng {
  std::mt19937_64 gen{20240611};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> unit{0.0, 1.0};
  Matrix3d gaussian() {
    Matrix3d m;
    for (int i = 0; i < 9; ++i) m(i) = normal(gen);
    return m;
  }
  Matrix3d rotation() {
    Eigen::Quaterniond q(normal(gen), normal(gen), normal(gen), normal(gen));
    return q.normalized().toRotationMatrix();
  }
  // U diag(s) W^T with random rotations U, W: singular values |s|, det sign of prod(s).
  Matrix3d with_singular_values(const Vector3d& s) { return rotation() * s.asDiagonal() * rotation().transpose(); }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, unit(gen)); }
};

// The maximum of trace(R^T Q) over rotations R: s1 + s2 + sign(det Q) s3.
double best_trace(const Matrix3d& Q) {
  const Vector3d s = Eigen::JacobiSVD<Matrix3d>(Q).singularValues();
  return s(0) + s(1) + (Q.determinant() < 0 ? -s(2) : s(2));
}

// Everything that characterises the answer, whether or not it is unique.
void expect_closest_rotation(const Matrix3d& Q, const Matrix3d& M) {
  ASSERT_TRUE(M.allFinite()) << Q;
  EXPECT_LE((M.transpose() * M - Matrix3d::Identity()).norm(), 1e-12) << Q;
  EXPECT_NEAR(M.determinant(), 1.0, 1e-12) << Q;
  EXPECT_GE((M.transpose() * Q).trace(), best_trace(Q) - 1e-12 * (1.0 + Q.norm())) << Q;
}

// The answer is unique and stable to ~1e-16 / gap when the relevant singular gap is wide.
double uniqueness_gap(const Matrix3d& Q) {
  const Vector3d s = Eigen::JacobiSVD<Matrix3d>(Q).singularValues();
  return (Q.determinant() < 0 ? s(1) - s(2) : s(1) + s(2)) / s(0);
}

}  // namespace

TEST(Polar, KnownAnswers) {
  EXPECT_EQ(closest_rotation(Matrix3d::Identity()), Matrix3d::Identity());
  const Matrix3d R = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_LE((closest_rotation(R) - R).norm(), 1e-15);
  EXPECT_LE((closest_rotation(4.0 * R * Vector3d(1, 2, 3).asDiagonal()) - R).norm(), 1e-14);
  // Reflections: the smallest singular direction is the one flipped.
  EXPECT_LE((closest_rotation(Vector3d(3, 2, -1).asDiagonal()) - Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LE((closest_rotation(Vector3d(3, -2, 1).asDiagonal()).diagonal() - Vector3d(1, -1, -1)).norm(), 1e-15);
  // Rank 2: the third column is fixed by the other two.
  EXPECT_LE((closest_rotation(R * Vector3d(2, 1, 0).asDiagonal()) - R).norm(), 1e-14);
}

TEST(Polar, MatchesJacobiSvdOnRandomMatrices) {
  Rng rng;
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    Matrix3d Q;
    switch (i % 5) {
      case 0: Q = rng.gaussian(); break;  // either determinant sign
      case 1: Q = rng.rotation() * (Matrix3d::Identity() + rng.log_uniform(1e-9, 0.5) * rng.gaussian()); break;
      case 2:  // stretched, condition up to 1e4
        Q = rng.with_singular_values(Vector3d(rng.log_uniform(1e-2, 1e2), rng.log_uniform(1e-2, 1e2),
                                              rng.log_uniform(1e-2, 1e2)));
        break;
      case 3:  // inverted tets
        Q = rng.with_singular_values(Vector3d(rng.log_uniform(0.1, 10), rng.log_uniform(0.1, 10),
                                              -rng.log_uniform(0.1, 10)));
        break;
      default: Q = rng.log_uniform(1e-6, 1e6) * rng.gaussian(); break;  // any scale
    }
    const Matrix3d M = closest_rotation(Q);
    expect_closest_rotation(Q, M);
    if (uniqueness_gap(Q) > 1e-5) {
      ++compared;
      EXPECT_LE((M - closest_rotation_svd(Q)).norm(), 1e-9) << Q;
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(compared, 19000);
}

TEST(Polar, NearSingularReflectedAndRankDeficient) {
  Rng rng;
  for (int i = 0; i < 3000; ++i) {
    const double tiny = std::vector<double>{1e-6, 1e-9, 1e-12, 1e-15, 0.0}[static_cast<size_t>(i % 5)];
    const double sign = (i / 5) % 2 ? 1.0 : -1.0;
    const double s0 = rng.log_uniform(0.5, 2), s1 = rng.log_uniform(0.1, 1);
    const Matrix3d Q = rng.with_singular_values(Vector3d(s0, s1, sign * tiny));
    const Matrix3d M = closest_rotation(Q);
    expect_closest_rotation(Q, M);
    EXPECT_LE((M - closest_rotation_svd(Q)).norm(), 1e-9) << Q;
    // Rank 1 and 0: many minimisers; any rotation reaching the best trace will do.
    const Matrix3d low_rank = rng.with_singular_values(Vector3d(s0, tiny, 0.0));
    expect_closest_rotation(low_rank, closest_rotation(low_rank));
    if (::testing::Test::HasFailure()) return;
  }
  expect_closest_rotation(Matrix3d::Zero(), closest_rotation(Matrix3d::Zero()));
}

// For det Q > 0 the answer is the polar factor Q (Q^T Q)^-1/2: an independent formula.
TEST(Polar, EqualsPolarFactorForPositiveDeterminant) {
  Rng rng;
  for (int i = 0; i < 2000; ++i) {
    Matrix3d Q = rng.with_singular_values(
        Vector3d(rng.log_uniform(0.05, 20), rng.log_uniform(0.05, 20), rng.log_uniform(0.05, 20)));
    const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(Q.transpose() * Q);
    const Matrix3d P_inv = eig.operatorInverseSqrt();
    EXPECT_LE((closest_rotation(Q) - Q * P_inv).norm(), 1e-9) << Q;
  }
}

TEST(Polar, ScaleInvariantAndDeterministic) {
  Rng rng;
  for (int i = 0; i < 500; ++i) {
    const Matrix3d Q = rng.gaussian();
    const Matrix3d M = closest_rotation(Q);
    const Matrix3d again = closest_rotation(Q);
    EXPECT_EQ(M, again);
    EXPECT_LE((closest_rotation(1e5 * Q) - M).norm(), 1e-9);
    EXPECT_LE((closest_rotation(1e-5 * Q) - M).norm(), 1e-9);
  }
}

TEST(Polar, NonFiniteGivesNanWithoutThrowing) {
  Matrix3d Q = Matrix3d::Identity();
  Q(1, 2) = std::nan("");
  EXPECT_TRUE(closest_rotation(Q).array().isNaN().all());
  Q(1, 2) = INFINITY;
  EXPECT_TRUE(closest_rotation(Q).array().isNaN().all());
  EXPECT_TRUE(closest_rotation_svd(Q).array().isNaN().all());
}
