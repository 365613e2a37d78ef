// slim::min_rotation against the O(n³) long-double reference, closed-form answers, and its
// sign conventions. SLIM_SWEEP_SCALE=<m> multiplies the random sweeps' instance counts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "core/min_rotation.h"
#include "core/surface.h"
#include "support/min_rotation_reference.h"
#include "support/shapes.h"

using namespace slim;
using slim::test::random_in_cap;
using slim::test::random_normals_in_cap;
using slim::test::random_unit_vector;

namespace {

const double kDeg = M_PI / 180.0;
const double kTaus[] = {0.0, std::sin(15 * kDeg), std::sin(30 * kDeg), std::sin(45 * kDeg)};

int scaled(int count) {
  const char* scale = std::getenv("SLIM_SWEEP_SCALE");
  return scale ? count * std::max(1, std::atoi(scale)) : count;
}

// What every result must satisfy, feasible or not.
void expect_well_formed(const MinRotation& r, const Eigen::Vector3d& d) {
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
void expect_safe(const MinRotation& r, const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau) {
  if (!r.feasible) return;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (normals.col(i).norm() == 0.0) continue;
    EXPECT_GE((r.rotation * normals.col(i).normalized()).dot(d), -tau - 1e-9) << "normal " << i;
  }
}

enum class Mix { Uniform, AroundDown, Groups, AntipodalPairs, NearDuplicates, TightCluster };

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

Eigen::Matrix3Xd cube_normals(const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity()) {
  Eigen::Matrix3Xd n(3, 6);
  n << 1, -1, 0, 0, 0, 0,  //
      0, 0, 1, -1, 0, 0,   //
      0, 0, 0, 0, 1, -1;
  return turn * n;
}

}  // namespace

// ---- exactness: 20,300 random instances against the reference --------------------------------

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

// ---- closed-form answers -------------------------------------------------------------------

TEST(MinRotation, AlreadySafeIsTheIdentity) {
  std::mt19937 rng(1);
  const Eigen::Vector3d d = random_unit_vector(rng);
  const Eigen::Matrix3Xd normals = random_normals_in_cap(rng, 50, d, 80 * kDeg);
  const MinRotation r = min_rotation(normals, d, std::sin(30 * kDeg));
  EXPECT_TRUE(r.feasible);
  EXPECT_EQ(r.angle, 0.0);
  EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
  EXPECT_LT((r.closest - d).norm(), 1e-15);
  expect_well_formed(r, d);
}

TEST(MinRotation, NoFacesOrOnlyZeroFacesIsTheIdentity) {
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  for (const Eigen::Matrix3Xd& normals : {Eigen::Matrix3Xd(3, 0), Eigen::Matrix3Xd(Eigen::Matrix3Xd::Zero(3, 4))}) {
    const MinRotation r = min_rotation(normals, d, 0.5);
    EXPECT_TRUE(r.feasible);
    EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
    expect_well_formed(r, d);
  }
}

TEST(MinRotation, ZeroNormalsAreIgnored) {
  std::mt19937 rng(2);
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3Xd risky = random_normals_in_cap(rng, 10, -d, 40 * kDeg);
  Eigen::Matrix3Xd with_zeros = Eigen::Matrix3Xd::Zero(3, 13);
  with_zeros.leftCols(10) = risky;
  const MinRotation a = min_rotation(risky, d, 0.3), b = min_rotation(with_zeros, d, 0.3);
  EXPECT_EQ(a.closest, b.closest);
  EXPECT_EQ(a.rotation, b.rotation);
}

TEST(MinRotation, SingleFaceStraightDownTurnsBy45DegreesAt45) {
  const double tau = std::sin(45 * kDeg);
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3Xd down = -d;
  const MinRotation r = min_rotation(down, d, tau);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.angle, 45 * kDeg, 1e-12);
  // Default tie-break: +X projected perpendicular to d, so the face tips towards +X.
  EXPECT_LT((r.closest - Eigen::Vector3d(std::cos(45 * kDeg), 0, tau)).norm(), 1e-12);
  EXPECT_NEAR((r.rotation * down.col(0)).dot(d), -tau, 1e-12);  // exactly on the threshold
  expect_well_formed(r, d);
}

TEST(MinRotation, JustRiskyFaceNeedsATinyTurn) {
  const double tau = std::sin(30 * kDeg), excess = 1e-5;
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  // 90° + alpha_max + excess from d: risky by `excess` radians.
  const Eigen::Matrix3Xd n = test::axis_angle(Eigen::Vector3d::UnitY(), (120 * kDeg) + excess) * d;
  const MinRotation r = min_rotation(n, d, tau);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.angle, excess, 1e-12);
  EXPECT_NEAR((r.rotation * n.col(0)).dot(d), -tau, 1e-12);
  expect_well_formed(r, d);
}

TEST(MinRotation, CubeIsInfeasibleBelowOneOverRoot3AndFeasibleAbove) {
  std::mt19937 rng(3);
  const double critical = 1.0 / std::sqrt(3.0);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d turn = test::axis_angle(random_unit_vector(rng), 2 * M_PI * k / 20.0);
    const Eigen::Vector3d d = random_unit_vector(rng);
    for (double tau : {0.0, 0.3, critical - 1e-6}) EXPECT_FALSE(min_rotation(cube_normals(turn), d, tau).feasible);
    for (double tau : {critical + 1e-6, 0.6, 0.9}) {
      const MinRotation r = min_rotation(cube_normals(turn), d, tau);
      EXPECT_TRUE(r.feasible) << tau;
      expect_well_formed(r, d);
      expect_safe(r, cube_normals(turn), d, tau);
    }
  }
}

TEST(MinRotation, CubeTieGoesToTheArcEndTowardsTieBreak) {
  // Axis-aligned cube, d = +Z, tau = 0.6: every point with p_z = 0.6 and |p_x|, |p_y| <= 0.6 is
  // equally near (angle acos 0.6). The tie-break +X picks the arc end p_x = 0.6.
  const MinRotation r = min_rotation(cube_normals(), Eigen::Vector3d::UnitZ(), 0.6);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.angle, std::acos(0.6), 1e-12);
  EXPECT_NEAR(r.closest.x(), 0.6, 1e-12);
  EXPECT_NEAR(std::abs(r.closest.y()), std::sqrt(1 - 2 * 0.36), 1e-12);
  EXPECT_EQ(r.closest, min_rotation(cube_normals(), Eigen::Vector3d::UnitZ(), 0.6).closest);
}

TEST(MinRotation, AntipodalPairAtTauZeroLeavesAGreatCircleThatSamplingMisses) {
  std::mt19937 rng(4);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Vector3d m = random_unit_vector(rng), d = random_unit_vector(rng);
    Eigen::Matrix3Xd pair(3, 2);
    pair << m, -m;
    const MinRotation r = min_rotation(pair, d, 0.0);
    ASSERT_TRUE(r.feasible);
    EXPECT_NEAR(r.closest.dot(m), 0.0, 1e-12);  // on the great circle m·p = 0
    EXPECT_NEAR(r.angle, std::abs(M_PI / 2 - std::acos(m.dot(d))), 1e-9);
    expect_well_formed(r, d);
    expect_safe(r, pair, d, 0.0);
    EXPECT_TRUE(std::isinf(test::sampled_min_angle(pair, d, 0.0, 20000)));
  }
}

TEST(MinRotation, AntipodalPairAboveTauZeroLeavesABand) {
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ(), m = Eigen::Vector3d(1, 0, 1).normalized();
  Eigen::Matrix3Xd pair(3, 2);
  pair << m, -m;
  const double tau = std::sin(15 * kDeg);
  const MinRotation r = min_rotation(pair, d, tau);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.closest.dot(m), tau, 1e-12);  // the band |p·m| <= tau, its edge nearest to d
  EXPECT_NEAR(r.angle, 45 * kDeg - 15 * kDeg, 1e-12);
}

TEST(MinRotation, DuplicatesChangeNothing) {
  std::mt19937 rng(5);
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3Xd base = random_normals_in_cap(rng, 6, -d, 50 * kDeg);
  Eigen::Matrix3Xd repeated(3, 18);
  repeated << base, base, base;
  for (double tau : kTaus) {
    const MinRotation a = min_rotation(base, d, tau), b = min_rotation(repeated, d, tau);
    EXPECT_EQ(a.feasible, b.feasible);
    EXPECT_NEAR(a.angle, b.angle, 1e-12);
  }
}

TEST(MinRotation, NearDuplicatePairMeetsOnItsBisector) {
  // Two risky faces mirrored through a plane containing d: every point of either circle nearest to
  // d lies inside the other cap, so the answer is where the two nearly equal circles cross. Below
  // a separation of about 1e-5 the circle points are inside the other cap by less than the
  // feasibility tolerance, so they count too; then only the angle is pinned down.
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  for (double separation : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    for (double tau : kTaus) {
      Eigen::Matrix3Xd pair(3, 2);
      pair << Eigen::Vector3d(separation / 2, 0.3, -0.9).normalized(),
          Eigen::Vector3d(-separation / 2, 0.3, -0.9).normalized();
      const MinRotation r = min_rotation(pair, d, tau);
      const test::ReferenceMinRotation ref = test::reference_min_rotation(pair, d, tau);
      SCOPED_TRACE("separation " + std::to_string(separation) + ", tau " + std::to_string(tau));
      ASSERT_TRUE(r.feasible && ref.feasible);
      EXPECT_NEAR(r.angle, static_cast<double>(ref.angle), 1e-9);
      if (separation >= 1e-4) {
        EXPECT_NEAR(r.closest.x(), 0.0, 1e-12);  // on the bisector, so on both circles
        for (int i = 0; i < 2; ++i) EXPECT_NEAR(pair.col(i).dot(r.closest), -tau, 1e-12);
      }
      expect_well_formed(r, d);
      expect_safe(r, pair, d, tau);
    }
  }
}

// Regular, symmetric normal sets are full of co-circular quadruples and exact ties: the hull
// that prunes the crossings must notice and fall back, and the answer must stay exact.
TEST(MinRotation, StructuredNormalsAgreeWithReference) {
  std::vector<Eigen::Matrix3Xd> sets;
  Eigen::Matrix3Xd rings(3, 6 * 16);  // a UV sphere's lower half: 6 latitudes x 16 longitudes
  for (int ring = 0; ring < 6; ++ring)
    for (int k = 0; k < 16; ++k) {
      const double polar = M_PI / 2 + (ring + 1) * M_PI / 14, azimuth = 2 * M_PI * k / 16;
      rings.col(ring * 16 + k) << std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar);
    }
  sets.push_back(rings);
  const Points ico = face_normals(test::icosphere(2));
  sets.push_back(ico.transpose());
  Eigen::Matrix3Xd lower = sets.back();
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < lower.cols(); ++i)
    if (lower(2, i) < 0.1) lower.col(kept++) = lower.col(i);
  sets.push_back(lower.leftCols(kept));
  std::mt19937 rng(8);
  for (size_t set = 0; set < sets.size(); ++set) {
    for (int k = 0; k < 12; ++k) {
      const double tau = kTaus[k % 4];
      const Eigen::Vector3d d = k < 4 ? Eigen::Vector3d::UnitZ() : random_unit_vector(rng);
      const MinRotation r = min_rotation(sets[set], d, tau);
      const test::ReferenceMinRotation ref = test::reference_min_rotation(sets[set], d, tau);
      SCOPED_TRACE("set " + std::to_string(set) + ", case " + std::to_string(k));
      ASSERT_EQ(r.feasible, ref.feasible);
      if (r.feasible) {
        EXPECT_NEAR(r.angle, static_cast<double>(ref.angle), 1e-9);
      }
      expect_well_formed(r, d);
      expect_safe(r, sets[set], d, tau);
    }
  }
}

TEST(MinRotation, ThousandsOfNormals) {
  std::mt19937 rng(6);
  const Eigen::Vector3d d = random_unit_vector(rng);
  const Eigen::Matrix3Xd normals = random_normals_in_cap(rng, 2000, random_in_cap(rng, -d, 30 * kDeg), 40 * kDeg);
  const double tau = std::sin(45 * kDeg);
  const MinRotation r = min_rotation(normals, d, tau);
  const test::ReferenceMinRotation ref = test::reference_min_rotation(normals, d, tau);
  ASSERT_TRUE(r.feasible && ref.feasible);
  EXPECT_NEAR(r.angle, static_cast<double>(ref.angle), 1e-9);
  expect_well_formed(r, d);
  expect_safe(r, normals, d, tau);
}

// ---- the tie-break for faces pointing straight down ------------------------------------------

TEST(MinRotationTieBreak, StraightDownFaceTipsTowardsTieBreak) {
  std::mt19937 rng(7);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d d = random_unit_vector(rng), tie = random_unit_vector(rng);
    const double tau = kTaus[k % 4];
    MinRotationOptions options;
    options.tie_break = tie;
    const Eigen::Matrix3Xd down = -d;
    const MinRotation r = min_rotation(down, d, tau, options);
    const Eigen::Vector3d t = (tie - tie.dot(d) * d).normalized();
    ASSERT_TRUE(r.feasible);
    EXPECT_LT((r.closest - (tau * d + std::sqrt(1 - tau * tau) * t)).norm(), 1e-12);
    EXPECT_LT((r.axis - t.cross(d)).norm(), 1e-12);
    // Bit-for-bit the same on a second call.
    const MinRotation again = min_rotation(down, d, tau, options);
    EXPECT_EQ(r.closest, again.closest);
    EXPECT_EQ(r.rotation, again.rotation);
  }
}

TEST(MinRotationTieBreak, NearlyStraightDownAndRepeatedFacesStillFollowTheTieBreak) {
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  MinRotationOptions options;
  options.tie_break = Eigen::Vector3d(0, 1, 0);
  Eigen::Matrix3Xd faces(3, 3);
  faces << -d, Eigen::Vector3d(1e-12, 0, -1).normalized(), -d;  // 1e-12 rad off: inside the tolerance
  const double tau = 0.5;
  const MinRotation r = min_rotation(faces, d, tau, options);
  ASSERT_TRUE(r.feasible);
  EXPECT_LT((r.closest - Eigen::Vector3d(0, std::sqrt(0.75), 0.5)).norm(), 1e-9);
  expect_safe(r, faces, d, tau);
}

TEST(MinRotationTieBreak, DefaultFallsBackToYWhenDIsAlongX) {
  const Eigen::Vector3d d = Eigen::Vector3d::UnitX();
  const Eigen::Matrix3Xd down = -d;
  const MinRotation r = min_rotation(down, d, 0.0);
  EXPECT_LT((r.closest - Eigen::Vector3d::UnitY()).norm(), 1e-12);
}

TEST(MinRotationTieBreak, OnlyTheAntipodeIsFeasible) {
  // tau = 0: the normals ±X and ±Y pin p to ±Z, and -Z forbids +Z: the only feasible point is
  // -d, where the rotation axis is undefined and comes from the tie-break (+X: axis X × d).
  Eigen::Matrix3Xd faces(3, 5);
  faces << 1, -1, 0, 0, 0,  //
      0, 0, 1, -1, 0,       //
      0, 0, 0, 0, -1;
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const MinRotation r = min_rotation(faces, d, 0.0);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.angle, M_PI, 1e-12);
  EXPECT_LT((r.closest + d).norm(), 1e-12);
  EXPECT_LT((r.axis - Eigen::Vector3d::UnitX().cross(d)).norm(), 1e-12);
  expect_well_formed(r, d);
  expect_safe(r, faces, d, 0.0);
}

// ---- errors --------------------------------------------------------------------------------

TEST(MinRotationErrors, RejectsBadInput) {
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3Xd n = -d;
  EXPECT_NO_THROW(min_rotation(n, d, 0.5));
  n(2, 0) = -1.01;
  EXPECT_THROW(min_rotation(n, d, 0.5), std::invalid_argument);  // not unit
  n(2, 0) = std::nan("");
  EXPECT_THROW(min_rotation(n, d, 0.5), std::invalid_argument);
  n(2, 0) = -1.0;
  EXPECT_THROW(min_rotation(n, 2 * d, 0.5), std::invalid_argument);
  EXPECT_THROW(min_rotation(n, Eigen::Vector3d(0, 0, std::nan("")), 0.5), std::invalid_argument);
  for (double tau : {-0.1, 1.0, std::nan("")}) EXPECT_THROW(min_rotation(n, d, tau), std::invalid_argument);
  MinRotationOptions options;
  options.tie_tolerance = -1;
  EXPECT_THROW(min_rotation(n, d, 0.5, options), std::invalid_argument);
}
