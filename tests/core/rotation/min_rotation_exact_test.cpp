// slim::min_rotation against the O(n³) long-double reference on random patches of every mix, and
// the reference against dense sampling. SLIM_SWEEP_SCALE=<m> multiplies the sweeps' instance counts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "core/geometry/surface.h"
#include "core/rotation/min_rotation.h"
#include "support/min_rotation_checks.h"
#include "support/min_rotation_reference.h"
#include "support/shapes.h"

using namespace slim;
using namespace slim::test;  // the checks, kDeg, kTaus, random normals

namespace {

int scaled(int count) {
  const char* scale = std::getenv("SLIM_SWEEP_SCALE");
  return scale ? count * std::max(1, std::atoi(scale)) : count;
}

enum class Mix { Uniform, AroundDown, Groups, AntipodalPairs, NearDuplicates, TightCluster, FloatGroups };

// A random risky-looking patch: around a downward direction within 60° of -d.
Eigen::Matrix3Xd around_down(std::mt19937& rng, int n, const Eigen::Vector3d& d) {
  std::uniform_real_distribution<double> spread(5 * kDeg, 60 * kDeg);
  return random_normals_in_cap(rng, n, random_in_cap(rng, -d, 60 * kDeg), spread(rng));
}

Eigen::Matrix3Xd random_normals(std::mt19937& rng, Mix mix, int n, const Eigen::Vector3d& d) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  switch (mix) {
    case Mix::Uniform:
      return random_normals_in_cap(rng, n, Eigen::Vector3d::UnitZ(), M_PI);
    case Mix::AroundDown:
      return around_down(rng, n, d);
    case Mix::Groups: {
      const int groups = 2 + static_cast<int>(unit(rng) * 2);
      Eigen::Matrix3Xd centres = random_normals_in_cap(rng, groups, -d, 100 * kDeg);
      Eigen::Matrix3Xd normals(3, n);
      for (int i = 0; i < n; ++i) normals.col(i) = random_in_cap(rng, centres.col(i % groups), 25 * kDeg);
      return normals;
    }
    case Mix::AntipodalPairs: {  // a patch plus 1-2 exact antipodal partners of its normals
      const int pairs = std::min(n / 2, 1 + static_cast<int>(unit(rng) * 2));
      Eigen::Matrix3Xd normals = around_down(rng, n, d);
      for (int p = 0; p < pairs; ++p) normals.col(n - 1 - p) = -normals.col(p);
      return normals;
    }
    case Mix::TightCluster: {  // a scan's tet: a hundred normals or more within a degree or two
      std::uniform_real_distribution<double> spread(0.1 * kDeg, 2.0 * kDeg);
      return random_normals_in_cap(rng, n, random_in_cap(rng, -d, 60 * kDeg), spread(rng));
    }
    case Mix::FloatGroups: {  // a dense mesh's tet: groups of 2-6 normals 1e-5..1e-4 apart (a
                              // subdivided face, vertices stored as floats), the groups within 1-10°
      std::uniform_real_distribution<double> spread(1.0 * kDeg, 10.0 * kDeg);
      const Eigen::Matrix3Xd centres = random_normals_in_cap(rng, n, random_in_cap(rng, -d, 60 * kDeg), spread(rng));
      Eigen::Matrix3Xd normals(3, n);
      for (int i = 0, group = 0; i < n; ++group) {
        const int size = std::min(n - i, 2 + static_cast<int>(unit(rng) * 5));
        for (int k = 0; k < size; ++k, ++i) normals.col(i) = random_in_cap(rng, centres.col(group), std::pow(10.0, -5.0 + unit(rng)));
      }
      return normals;
    }
    case Mix::NearDuplicates: {  // exact copies and copies moved by 1e-12..1e-6 radians
      Eigen::Matrix3Xd normals = around_down(rng, n, d);
      for (int i = 1; i < n; ++i) {
        if (unit(rng) < 0.5) continue;
        const Eigen::Vector3d original = normals.col(static_cast<int>(unit(rng) * i));
        const double nudge = unit(rng) < 0.2 ? 0.0 : std::pow(10.0, -12.0 + 6.0 * unit(rng));
        normals.col(i) = random_in_cap(rng, original, nudge);
      }
      return normals;
    }
  }
  return {};
}

struct SweepCount {
  int feasible = 0, infeasible = 0;
};

// Random instances of one mix, each compared with the reference; stops at the first bad instance.
SweepCount sweep(Mix mix, int instances, int min_n, int max_n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> count(min_n, max_n);
  SweepCount seen;
  for (int k = 0; k < instances; ++k) {
    const double tau = kTaus[k % 4];
    const int n = count(rng);
    const Eigen::Vector3d d = k % 2 ? Eigen::Vector3d::UnitZ() : random_unit_vector(rng);
    const Eigen::Matrix3Xd normals = random_normals(rng, mix, n, d);
    const MinRotation r = min_rotation(normals, d, tau);
    const test::ReferenceMinRotation ref = test::reference_min_rotation(normals, d, tau);
    SCOPED_TRACE("instance " + std::to_string(k) + ", n = " + std::to_string(n) + ", tau = " + std::to_string(tau));
    expect_well_formed(r, d);
    expect_safe(r, normals, d, tau);
    EXPECT_EQ(r.feasible, ref.feasible);
    if (r.feasible && ref.feasible) {
      EXPECT_LE(r.angle, static_cast<double>(ref.angle) + 1e-6);
      EXPECT_GE(r.angle, static_cast<double>(ref.angle) - 1e-6);
    }
    (r.feasible ? seen.feasible : seen.infeasible)++;
    if (::testing::Test::HasFailure()) break;
  }
  return seen;
}

}  // namespace

// ---- exactness: 20,900 random instances against the reference --------------------------------

TEST(MinRotationExact, UniformNormals) {
  const SweepCount seen = sweep(Mix::Uniform, scaled(4000), 1, 100, 101);
  EXPECT_GT(seen.feasible, 400);  // both outcomes are exercised
  EXPECT_GT(seen.infeasible, 400);
}

TEST(MinRotationExact, ClusteredAroundDown) {
  const SweepCount seen = sweep(Mix::AroundDown, scaled(4000), 1, 100, 202);
  EXPECT_GT(seen.feasible, 2000);
}

TEST(MinRotationExact, TwoOrThreeGroups) {
  const SweepCount seen = sweep(Mix::Groups, scaled(4000), 1, 100, 303);
  EXPECT_GT(seen.feasible, 400);
  EXPECT_GT(seen.infeasible, 100);
}

TEST(MinRotationExact, PlantedAntipodalPairs) {
  const SweepCount seen = sweep(Mix::AntipodalPairs, scaled(4000), 1, 100, 404);
  EXPECT_GT(seen.feasible, 400);
  EXPECT_GT(seen.infeasible, 100);
}

TEST(MinRotationExact, NearDuplicates) {
  const SweepCount seen = sweep(Mix::NearDuplicates, scaled(4000), 1, 100, 505);
  EXPECT_GT(seen.feasible, 2000);
}

// Where the hull of the normals cannot be trusted (nearly co-circular ones in a tight cluster),
// the answer comes from a few of them at a time (an active set), checked against all.
TEST(MinRotationExact, TightClustersOfAScansTet) {
  const SweepCount seen = sweep(Mix::TightCluster, scaled(300), 24, 400, 707);
  EXPECT_GT(seen.feasible, 250);
}

// The same with the normals of a dense surface in tight groups: the active set takes one of a
// group at a time, and the answer must still be the reference's.
TEST(MinRotationExact, GroupsOfADenseSurfacesTet) {
  const SweepCount seen = sweep(Mix::FloatGroups, scaled(300), 24, 400, 808);
  EXPECT_GT(seen.feasible, 250);
}

TEST(MinRotationExact, LargePatches) {
  for (Mix mix : {Mix::AroundDown, Mix::Groups, Mix::AntipodalPairs, Mix::NearDuplicates, Mix::Uniform})
    sweep(mix, scaled(60), 100, 500, 606 + static_cast<unsigned>(mix));
}

// The reference itself against dense sampling: no sampled feasible point is nearer than its
// answer, and where sampling sees a region, it sees it near the reference's answer.
TEST(MinRotationReference, AgreesWithDenseSampling) {
  std::mt19937 rng(707);
  std::uniform_int_distribution<int> count(1, 8);
  int sampled_feasible = 0, sampled_close = 0;
  for (int k = 0; k < 300; ++k) {
    const double tau = kTaus[k % 4];
    const Eigen::Vector3d d = random_unit_vector(rng);
    const Mix mix = k % 3 == 0 ? Mix::Uniform : (k % 3 == 1 ? Mix::AroundDown : Mix::Groups);
    const Eigen::Matrix3Xd normals = random_normals(rng, mix, count(rng), d);
    const test::ReferenceMinRotation ref = test::reference_min_rotation(normals, d, tau);
    const double sampled = test::sampled_min_angle(normals, d, tau, 20000);
    SCOPED_TRACE("case " + std::to_string(k));
    if (ref.feasible) {
      for (Eigen::Index i = 0; i < normals.cols(); ++i) EXPECT_GE(normals.col(i).dot(ref.closest), -tau - 1e-9);
    }
    if (std::isfinite(sampled)) {
      ++sampled_feasible;
      ASSERT_TRUE(ref.feasible);
      EXPECT_LE(static_cast<double>(ref.angle), sampled + 1e-9);
      if (sampled - static_cast<double>(ref.angle) < 0.05) ++sampled_close;
    }
  }
  EXPECT_GT(sampled_feasible, 100);
  EXPECT_GE(sampled_close, 0.9 * sampled_feasible);
}
