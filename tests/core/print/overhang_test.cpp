// Known answers for the risky-face rule n·d + tau < 0 and the build-plate exemption.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/platform/parallel_for.h"
#include "core/print/overhang.h"
#include "support/shapes.h"

using namespace slim;

TEST(Overhang, CubeOnThePlateHasNoRiskyArea) {
  const OverhangReport r = analyse_overhang(test::box({0, 0, 0}, {10, 10, 10}));
  EXPECT_EQ(r.risky_count, 0);
  EXPECT_EQ(r.risky_area, 0.0);
  EXPECT_EQ(r.plate_count, 2);  // the bottom square, two triangles
  EXPECT_NEAR(r.total_area, 600.0, 1e-9);
}

TEST(Overhang, CubeBottomIsRiskyWithoutThePlateRule) {
  PrintSetup o;
  o.plate = PlateRule::none();
  const OverhangReport r = analyse_overhang(test::box({0, 0, 0}, {10, 10, 10}), o);
  EXPECT_EQ(r.risky_count, 2);
  EXPECT_NEAR(r.risky_area, 100.0, 1e-9);
}

TEST(Overhang, TShapeArmUndersidesAreExactlyTheRiskyArea) {
  const test::TShape p;
  for (double alpha : {0.0, 30.0, 45.0, 60.0, 89.0}) {
    PrintSetup o;
    o.alpha_max_deg = alpha;
    const OverhangReport r = analyse_overhang(test::t_shape(p), o);
    EXPECT_NEAR(r.risky_area, test::t_shape_arm_underside_area(p), 1e-9) << "alpha " << alpha;
    EXPECT_EQ(r.plate_count, 2);  // the stem's foot
  }
}

TEST(Overhang, ShadowVolumeIsThePrismBetweenTheOverhangsAndThePlate) {
  // The T's arm undersides are flat, face straight down and sit at the stem's height: the shadow
  // is exactly the empty box under the arms, whatever the angle.
  const test::TShape p;
  const double under_arms = test::t_shape_arm_underside_area(p) * p.height;
  for (double alpha : {0.0, 45.0, 89.0}) {
    PrintSetup o;
    o.alpha_max_deg = alpha;
    EXPECT_NEAR(analyse_overhang(test::t_shape(p), o).shadow_volume, under_arms, 1e-9 * under_arms) << "alpha " << alpha;
  }
  // Lifting the part lifts nothing: heights count from the part's own lowest point.
  const Surface lifted = test::transformed(test::t_shape(p), Eigen::Matrix3d::Identity(), {0, 0, 100});
  EXPECT_NEAR(analyse_overhang(lifted).shadow_volume, under_arms, 1e-9 * under_arms);
}

TEST(Overhang, ShadowVolumeOfATiltedOverhangCountsItsFootprint) {
  // A cube's bottom face without the plate rule, turned about x: at 30 degrees from flat it is
  // still risky at alpha 45 and its footprint is area * cos(30); its centroid rises with the turn.
  const double side = 10.0, turn = 30.0 * M_PI / 180.0;
  const Surface cube = test::transformed(test::box({-5, -5, -5}, {5, 5, 5}), test::axis_angle({1, 0, 0}, turn));
  PrintSetup o;
  o.plate = PlateRule::none();
  const OverhangReport r = analyse_overhang(cube, o);
  const Points n = face_normals(cube);
  const Eigen::VectorXd area = face_areas(cube);
  double expected = 0.0;
  for (Eigen::Index f = 0; f < cube.F.rows(); ++f) {
    if (!r.risky[static_cast<size_t>(f)]) continue;
    const double centroid_z = (cube.V(cube.F(f, 0), 2) + cube.V(cube.F(f, 1), 2) + cube.V(cube.F(f, 2), 2)) / 3.0;
    expected += area(f) * -n(f, 2) * (centroid_z - r.plate_height);
  }
  EXPECT_EQ(r.risky_count, 2);  // only the turned bottom: the side that went down is at 30 degrees from vertical
  EXPECT_NEAR(r.risky_area, side * side, 1e-9);
  EXPECT_NEAR(r.shadow_volume, expected, 1e-9 * expected);
  // The bottom face's centre sits 5 below the cube's centre, turned by 50 degrees; the lowest
  // corner is the cube's lowest point.
  const double centre_above_plate = -r.plate_height - 5.0 * std::cos(turn);
  EXPECT_NEAR(r.shadow_volume, side * side * std::cos(turn) * centre_above_plate, 1e-6);
}

TEST(Overhang, IcosphereRiskyAreaMatchesTheSphericalCap) {
  const double r = 10.0;
  const Surface sphere = test::icosphere(5, r);
  for (double alpha : {0.0, 15.0, 30.0, 45.0, 60.0}) {
    PrintSetup o;
    o.alpha_max_deg = alpha;
    o.plate = PlateRule::none();  // the whole lower cap counts
    const OverhangReport rep = analyse_overhang(sphere, o);
    // Points of the sphere with n·z < -sin(alpha): a cap of height r (1 - sin(alpha)).
    const double expected = 2.0 * M_PI * r * r * (1.0 - std::sin(alpha * M_PI / 180.0));
    EXPECT_NEAR(rep.risky_area / expected, 1.0, 0.02) << "alpha " << alpha;
  }
}

TEST(Overhang, UpsideDownFaceIsRiskyExactlyWhenItsOriginalFacedUpSteeply) {
  const double alpha = 40.0;
  const double tau = std::sin(alpha * M_PI / 180.0);
  const Surface sphere = test::icosphere(3, 10.0);
  const Surface flipped = test::transformed(sphere, test::axis_angle({1, 0.3, 0}, M_PI));
  PrintSetup o;
  o.alpha_max_deg = alpha;
  o.plate = PlateRule::none();
  const OverhangReport r = analyse_overhang(flipped, o);
  const Points n0 = face_normals(sphere);
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    const double up = n0(f, 2);
    if (std::abs(up - tau) < 1e-9) continue;  // on the threshold: either verdict is rounding
    EXPECT_EQ(r.risky[static_cast<size_t>(f)], up > tau) << "face " << f;
  }
}

TEST(Overhang, PrintDirectionNeedNotBeUnitOrVertical) {
  // A box printed along +X: the face at x = lo is on the plate, the face at x = hi is safe, the
  // four side faces are vertical (n·d = 0) and safe.
  PrintSetup o;
  o.direction = {3.0, 0.0, 0.0};
  const OverhangReport r = analyse_overhang(test::box({0, 0, 0}, {2, 2, 2}), o);
  EXPECT_EQ(r.risky_count, 0);
  EXPECT_EQ(r.plate_count, 2);
  EXPECT_NEAR(r.plate_height, 0.0, 1e-12);
}

TEST(Overhang, QualityIsNdPlusTauAndPlateFacesReadSafe) {
  const Surface s = test::t_shape();
  const OverhangReport r = analyse_overhang(s);
  const Points n = face_normals(s);
  const double tau = std::sin(M_PI / 4);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (r.on_plate[static_cast<size_t>(f)])
      EXPECT_EQ(r.quality(f), 1.0);
    else
      EXPECT_NEAR(r.quality(f), n(f, 2) + tau, 1e-12);
    EXPECT_EQ(r.risky[static_cast<size_t>(f)], r.quality(f) < 0.0);
  }
}

TEST(Overhang, BadInputIsRefusedWithAReason) {
  EXPECT_THROW(analyse_overhang(Surface{}), std::invalid_argument);
  PrintSetup o;
  o.alpha_max_deg = 90.0;
  EXPECT_THROW(analyse_overhang(test::box({0, 0, 0}, {1, 1, 1}), o), std::invalid_argument);
  o = {};
  o.direction = Eigen::Vector3d::Zero();
  EXPECT_THROW(analyse_overhang(test::box({0, 0, 0}, {1, 1, 1}), o), std::invalid_argument);
  try {
    analyse_overhang(Surface{});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no faces"), std::string::npos);
  }
}

TEST(Overhang, ZeroPlateToleranceMeansExactContact) {
  // The cube's bottom lies exactly at the lowest height: with a tolerance of 0 it still rests on
  // the plate (the rule is "within", inclusive); a face a hair above does not.
  PrintSetup o;
  o.plate = PlateRule::within(0.0);
  const OverhangReport r = analyse_overhang(test::box({0, 0, 0}, {10, 10, 10}), o);
  EXPECT_EQ(r.plate_count, 2);
  EXPECT_EQ(r.risky_count, 0);
  Surface lifted = test::box({0, 0, 0}, {10, 10, 10});
  for (Eigen::Index v = 0; v < lifted.V.rows(); ++v)
    if (lifted.V(v, 0) > 5 && lifted.V(v, 2) == 0.0) lifted.V(v, 2) = 1e-9;  // tilt the bottom a hair
  const OverhangReport tilted = analyse_overhang(lifted, o);
  EXPECT_LT(tilted.plate_count, 2);
  EXPECT_GT(tilted.risky_count, 0);
}

TEST(Overhang, AFaceExactlyOnTheThresholdIsSafe) {
  // At alpha_max = 0 (tau = 0) a vertical wall has n·d = 0 exactly: on the threshold, safe. Only
  // the bottom overhangs when the plate rule is off: 100 mm², not the walls' 400.
  PrintSetup o;
  o.alpha_max_deg = 0.0;
  o.plate = PlateRule::none();
  const OverhangReport r = analyse_overhang(test::box({0, 0, 0}, {10, 10, 10}), o);
  EXPECT_EQ(r.risky_count, 2);
  EXPECT_NEAR(r.risky_area, 100.0, 1e-9);
  for (Eigen::Index f = 0; f < r.quality.size(); ++f)
    if (r.quality(f) == 0.0) {
      EXPECT_FALSE(r.risky[static_cast<size_t>(f)]) << "face " << f;
    }
}

// The analysis takes each face on the threads and sums in face order: on a mesh large enough for
// the threads (81,920 faces, tilted so that a band of them overhangs), every figure is that of a
// plain pass face by face, to the bit, on one thread and on two.
TEST(Overhang, ALargeMeshGivesTheSumsOfOnePassFaceByFace) {
  Surface s = test::icosphere(6);
  s.V = s.V * test::axis_angle(Eigen::Vector3d(1, 2, 0).normalized(), 0.3).transpose();
  s.V.col(2).array() -= s.V.col(2).minCoeff();
  const double tolerance = 0.05;
  PrintSetup o;
  o.plate = PlateRule::within(tolerance);
  const double tau = std::sin(o.alpha_max_deg * M_PI / 180.0);
  const Eigen::VectorXd height = s.V.col(2);
  const double plate = height.minCoeff();
  double total = 0.0, risky_area = 0.0, deficit = 0.0, shadow = 0.0;
  int risky = 0, on_plate = 0;
  Eigen::VectorXd area(s.F.rows());
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    area(f) = 0.5 * cross.norm();
    const Eigen::Vector3d n = cross / cross.norm();
    const double q = n.z() + tau, h0 = height(s.F(f, 0)), h1 = height(s.F(f, 1)), h2 = height(s.F(f, 2));
    if (std::max({h0, h1, h2}) - plate <= tolerance) {
      ++on_plate;
    } else if (q < 0.0) {
      ++risky;
      risky_area += area(f);
      deficit -= area(f) * q;
      shadow += area(f) * -n.z() * ((h0 + h1 + h2) / 3.0 - plate);
    }
  }
  total = area.sum();
  ASSERT_GT(risky, 10000);
  ASSERT_GT(on_plate, 0);
  for (int threads : {1, 2}) {
    const ThreadScope scope(threads);
    const OverhangReport r = analyse_overhang(s, o);
    EXPECT_EQ(r.risky_count, risky) << threads;
    EXPECT_EQ(r.plate_count, on_plate) << threads;
    EXPECT_EQ(r.total_area, total) << threads;
    EXPECT_EQ(r.risky_area, risky_area) << threads;
    EXPECT_EQ(r.risky_deficit, deficit) << threads;
    EXPECT_EQ(r.shadow_volume, shadow) << threads;
  }
}
