// slim::min_rotation: closed-form answers, structured patches against the O(n³) long-double
// reference, its sign conventions and tie-break, and its refusals. The random sweeps against the
// reference are in min_rotation_exact_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
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

Eigen::Matrix3Xd cube_normals(const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity()) {
  Eigen::Matrix3Xd n(3, 6);
  n << 1, -1, 0, 0, 0, 0,  //
      0, 0, 1, -1, 0, 0,   //
      0, 0, 0, 0, 1, -1;
  return turn * n;
}

}  // namespace

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
