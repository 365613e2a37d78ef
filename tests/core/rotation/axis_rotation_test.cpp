// The smallest turn about a fixed axis: known answers, and a fine sweep of the angle as the oracle.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/rotation/axis_rotation.h"

using namespace slim;

namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();
const double kTau45 = std::sin(M_PI / 4);

bool all_safe(const Eigen::Matrix3Xd& normals, const Eigen::Matrix3d& R, double tau, double slack) {
  for (Eigen::Index i = 0; i < normals.cols(); ++i)
    if ((R * normals.col(i)).dot(kUp) + tau < -slack) return false;
  return true;
}

}  // namespace

TEST(AxisRotation, KnownAnswers) {
  Eigen::Matrix3Xd down(3, 1);
  down << 0, 0, -1;
  // Straight down about +X: the normal tilts towards +Y and is safe once cos θ <= tau.
  MinRotation r = min_rotation_about_axis(down, kUp, kTau45, Eigen::Vector3d::UnitX());
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.angle, M_PI / 4, 1e-12);
  EXPECT_TRUE(r.axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_NEAR((r.rotation * down.col(0)).dot(kUp), -kTau45, 1e-12);
  EXPECT_LT((r.closest - r.rotation.transpose() * kUp).norm(), 1e-15);
  // A face already safe needs no turn.
  Eigen::Matrix3Xd side(3, 1);
  side << 1, 0, 0;
  r = min_rotation_about_axis(side, kUp, kTau45, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(r.feasible);
  EXPECT_EQ(r.angle, 0.0);
  EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
  // Turning about the vertical never changes how much a face overhangs.
  r = min_rotation_about_axis(down, kUp, kTau45, kUp);
  EXPECT_FALSE(r.feasible);
  EXPECT_EQ(r.angle, 0.0);
  EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
  // A face 8 degrees off down, towards +X (a mushroom's cap): turned the short way (about -Y,
  // tilting further towards +X) it needs 37 degrees; the long way (about +Y) 53.
  Eigen::Matrix3Xd cap(3, 1);
  cap << std::sin(8 * M_PI / 180), 0, -std::cos(8 * M_PI / 180);
  EXPECT_NEAR(min_rotation_about_axis(cap, kUp, kTau45, -Eigen::Vector3d::UnitY()).angle, 37 * M_PI / 180, 1e-12);
  EXPECT_NEAR(min_rotation_about_axis(cap, kUp, kTau45, Eigen::Vector3d::UnitY()).angle, 53 * M_PI / 180, 1e-12);
}

TEST(AxisRotation, MatchesAFineSweepOfTheAngle) {
  std::mt19937 gen(11);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> count(1, 8);
  std::uniform_real_distribution<double> alpha(0.0, 80.0);
  const int sweep = 20000;
  int feasible = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = count(gen);
    Eigen::Matrix3Xd normals(3, n);
    for (int i = 0; i < n; ++i) {
      // Mostly downward faces, so that turning matters.
      Eigen::Vector3d v(g(gen), g(gen), g(gen) - 1.5);
      normals.col(i) = v.normalized();
    }
    const Eigen::Vector3d axis = Eigen::Vector3d(g(gen), g(gen), 0.3 * g(gen)).normalized();
    const double tau = std::sin(alpha(gen) * M_PI / 180);
    const MinRotation r = min_rotation_about_axis(normals, kUp, tau, axis);
    // The oracle: the first of `sweep` equally spaced angles in [0, π] at which every face is safe.
    int first = -1;
    for (int k = 0; k <= sweep && first < 0; ++k)
      if (all_safe(normals, Eigen::AngleAxisd(M_PI * k / sweep, axis).toRotationMatrix(), tau, 0.0)) first = k;
    const double step = M_PI / sweep;
    if (!r.feasible) {
      EXPECT_EQ(first, -1) << "trial " << trial;
      continue;
    }
    ++feasible;
    EXPECT_TRUE(all_safe(normals, r.rotation, tau, 1e-12)) << "trial " << trial;
    // Safe angles form closed arcs: the exact one lies at most a step before the swept one (or
    // the safe arc is thinner than a step, which the sweep can miss altogether).
    if (first >= 0) {
      EXPECT_LE(r.angle, first * step + 1e-12) << "trial " << trial;
      EXPECT_GE(r.angle, (first - 1) * step - 1e-12) << "trial " << trial;
    }
  }
  EXPECT_GT(feasible, 100);
}

TEST(AxisRotation, BadInputIsRefused) {
  Eigen::Matrix3Xd down(3, 1);
  down << 0, 0, -1;
  EXPECT_THROW(min_rotation_about_axis(down, kUp, 1.0, Eigen::Vector3d::UnitX()), std::invalid_argument);
  EXPECT_THROW(min_rotation_about_axis(down, kUp, kTau45, Eigen::Vector3d(2, 0, 0)), std::invalid_argument);
  EXPECT_THROW(min_rotation_about_axis(down, Eigen::Vector3d(0, 0, NAN), kTau45, Eigen::Vector3d::UnitX()),
               std::invalid_argument);
  Eigen::Matrix3Xd bad(3, 1);
  bad << 0, 0, -3;
  EXPECT_THROW(min_rotation_about_axis(bad, kUp, kTau45, Eigen::Vector3d::UnitX()), std::invalid_argument);
  // Zero-area faces do not constrain anything.
  Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, 2);
  const MinRotation r = min_rotation_about_axis(zero, kUp, kTau45, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(r.feasible);
  EXPECT_EQ(r.angle, 0.0);
}
