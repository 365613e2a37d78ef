// Checks every minimal rotation must pass (core/rotation/min_rotation.h), shared by the min_rotation tests:
// header-only, for test executables that link GoogleTest.
//   expect_well_formed(r, d)          a proper rotation turning r.closest onto d, the angle and axis
//                                     consistent; the identity when not feasible
//   expect_safe(r, normals, d, tau)   after r every (non-zero) face is safe
//   kDeg, kTaus                       degrees in radians; the taus the sweeps cycle through
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "core/rotation/min_rotation.h"

namespace slim::test {

inline const double kDeg = M_PI / 180.0;
inline const double kTaus[] = {0.0, std::sin(15 * kDeg), std::sin(30 * kDeg), std::sin(45 * kDeg)};

// What every result must satisfy, feasible or not.
inline void expect_well_formed(const MinRotation& r, const Eigen::Vector3d& d) {
  ASSERT_TRUE(r.closest.allFinite() && r.axis.allFinite() && r.rotation.allFinite() && std::isfinite(r.angle));
  const Eigen::Matrix3d& R = r.rotation;
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(r.closest.norm(), 1.0, 1e-12);
  EXPECT_NEAR(r.axis.norm(), 1.0, 1e-12);
  EXPECT_LT((R * r.closest - d).norm(), 1e-12);  // R turns the closest point onto d
  EXPECT_NEAR(r.angle, std::atan2(r.closest.cross(d).norm(), r.closest.dot(d)), 1e-12);
  EXPECT_NEAR(r.axis.dot(d), 0.0, 1e-9);
  // The axis is the right-handed one: turning by +angle about it is R.
  EXPECT_LT((Eigen::AngleAxisd(r.angle, r.axis).toRotationMatrix() - R).norm(), 1e-9);
  if (!r.feasible) {
    EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
    EXPECT_EQ(r.angle, 0.0);
    EXPECT_LT((r.closest - d).norm(), 1e-15);
  }
}

// After applying R every (non-zero) face is safe.
inline void expect_safe(const MinRotation& r, const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau) {
  if (!r.feasible) return;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (normals.col(i).norm() == 0.0) continue;
    EXPECT_GE((r.rotation * normals.col(i).normalized()).dot(d), -tau - 1e-9) << "normal " << i;
  }
}

}  // namespace slim::test
