// Normals closer than a tolerance are one constraint (core/rotation/near_repeats.h): the kept columns
// against a plain all-pairs search, and the minimal rotation of many nearly repeated normals
// against that of the distinct ones.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/rotation/min_rotation.h"
#include "core/rotation/near_repeats.h"
#include "support/min_rotation_reference.h"

namespace slim {
namespace {

const double kDeg = M_PI / 180.0;

// The first kept column within the tolerance of each, by trying every earlier column.
std::vector<Eigen::Index> all_pairs(const Eigen::Matrix3Xd& u, double tol) {
  std::vector<Eigen::Index> kept(static_cast<size_t>(u.cols()));
  for (Eigen::Index j = 0; j < u.cols(); ++j) {
    kept[static_cast<size_t>(j)] = j;
    for (Eigen::Index i = 0; i < j; ++i)
      if (kept[static_cast<size_t>(i)] == i && (u.col(i) - u.col(j)).norm() <= tol) {
        kept[static_cast<size_t>(j)] = i;
        break;
      }
  }
  return kept;
}

TEST(NearRepeats, KeepsWhatAnAllPairsSearchKeeps) {
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0.0, 1.0);
  for (double tol : {0.0, 1e-12, 1e-3, 0.05}) {
    // Clusters of nearly equal normals (some exactly equal, some within, some beyond the
    // tolerance of each other), shuffled.
    const Eigen::Matrix3Xd centres = test::random_normals_in_cap(rng, 12, Eigen::Vector3d::UnitZ(), 40 * kDeg);
    Eigen::Matrix3Xd u(3, 240);
    for (Eigen::Index i = 0; i < u.cols(); ++i) {
      const double size = std::array<double, 4>{0.0, 0.3, 1.0, 3.0}[static_cast<size_t>(i % 4)] * tol;
      const Eigen::Vector3d shift(jitter(rng), jitter(rng), jitter(rng));
      u.col(i) = (centres.col((i * 7) % 12) + size / std::sqrt(3.0) * shift).normalized();
    }
    const std::vector<Eigen::Index> kept = near_repeats(u, tol);
    EXPECT_EQ(kept, all_pairs(u, tol)) << tol;
  }
}

// A subdivided flat face gives hundreds of normals that differ only in their last bits: closer
// than the feasibility tolerance, they are one constraint, and the answer is that of the distinct
// normals alone, bit for bit (the first of each group is kept).
// The faces of a large flat feature: thousands of copies of a few normals that share their x
// (every one 0), the copies of one normal differing in their last bits. The same kept columns as
// the all-pairs search, whatever the tolerance.
TEST(NearRepeats, ThousandsOfCopiesSharingACoordinateKeepWhatAllPairsKeeps) {
  const std::array<Eigen::Vector3d, 4> normals{Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, -1, 0),
                                               Eigen::Vector3d(0, 0.6, -0.8)};
  Eigen::Matrix3Xd u(3, 20000);
  for (Eigen::Index j = 0; j < u.cols(); ++j) {
    u.col(j) = normals[static_cast<size_t>(j % 4)];
    u(1, j) += (j % 7) * 1e-16;
  }
  for (double tol : {0.0, 1e-6, 0.5}) EXPECT_EQ(near_repeats(u, tol), all_pairs(u, tol)) << tol;
}

TEST(NearRepeats, NormalsWithinTheToleranceAreOneMinimalRotationConstraint) {
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0.0, 1e-13);
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3Xd base = test::random_normals_in_cap(rng, 6, -d, 50 * kDeg);
  const int copies = 400;
  Eigen::Matrix3Xd many(3, base.cols() * copies);
  for (int c = 0; c < copies; ++c)
    for (Eigen::Index i = 0; i < base.cols(); ++i) {
      const Eigen::Vector3d shift(jitter(rng), jitter(rng), jitter(rng));
      many.col(c * base.cols() + i) = c == 0 ? Eigen::Vector3d(base.col(i)) : Eigen::Vector3d((base.col(i) + shift).normalized());
    }
  for (double tau : {0.0, std::sin(15 * kDeg), std::sin(30 * kDeg), std::sin(45 * kDeg)}) {
    const MinRotation a = min_rotation(base, d, tau), b = min_rotation(many, d, tau);
    EXPECT_EQ(a.feasible, b.feasible) << tau;
    EXPECT_EQ(a.closest, b.closest) << tau;
    EXPECT_EQ(a.angle, b.angle) << tau;
  }
}

}  // namespace
}  // namespace slim
