// What a deformation did to the part's proportions (core/geometry/proportions.h), against maps
// whose effect is known exactly and against brute force.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/geometry/proportions.h"
#include "support/shapes.h"

namespace slim {
namespace {

Points mapped(const Points& V, const Eigen::Matrix3d& A, const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  return (V * A.transpose()).rowwise() + t.transpose();
}

TEST(Proportions, AStretchReadsAsItselfAndARigidMotionAsNothing) {
  const Surface t = test::refined(test::t_shape(), 2);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  // 3% taller, 2% narrower in x.
  const Proportions stretched = proportions(t, mapped(t.V, Eigen::Vector3d(0.98, 1.0, 1.03).asDiagonal(), {5, -2, 1}), z);
  EXPECT_NEAR(stretched.extent_change_pct.x(), -2.0, 1e-9);
  EXPECT_NEAR(stretched.extent_change_pct.y(), 0.0, 1e-9);
  EXPECT_NEAR(stretched.extent_change_pct.z(), 3.0, 1e-9);
  EXPECT_NEAR(stretched.height_change_pct, 3.0, 1e-9);
  EXPECT_NEAR(stretched.affine_departure_pct, 3.0, 1e-9);
  EXPECT_EQ(stretched.folded_faces, 0);
  // A turn about the print direction and a shift: no change of height, none from rigid.
  const Eigen::Matrix3d turn = test::axis_angle(z, 0.7);
  const Proportions rigid = proportions(t, mapped(t.V, turn, {10, 20, 0}), z);
  EXPECT_NEAR(rigid.height_change_pct, 0.0, 1e-9);
  EXPECT_NEAR(rigid.affine_departure_pct, 0.0, 1e-9);
  EXPECT_EQ(rigid.folded_faces, 0);
  EXPECT_GT(std::abs(rigid.extent_change_pct.x()), 1.0);  // the box in x is another one
  // The height is along the print direction given.
  const Eigen::Vector3d d = Eigen::Vector3d(1, 0, 1).normalized();
  const Eigen::Matrix3d along_d = Eigen::Matrix3d::Identity() + 0.05 * d * d.transpose();
  const Proportions tilted = proportions(t, mapped(t.V, along_d), d);
  const Eigen::VectorXd h0 = t.V * d, h1 = mapped(t.V, along_d) * d;
  EXPECT_NEAR(tilted.height_change_pct, 100.0 * ((h1.maxCoeff() - h1.minCoeff()) / (h0.maxCoeff() - h0.minCoeff()) - 1.0), 1e-9);
  EXPECT_NEAR(tilted.height_change_pct, 5.0, 1e-9);
  EXPECT_NEAR(tilted.affine_departure_pct, 5.0, 1e-9);
}

TEST(Proportions, ALocalBendDepartsLittleFromRigid) {
  // One arm of the T bent up by a few mm: the extents move, the best affine map hardly does.
  const Surface t = test::refined(test::t_shape(), 3);
  Points bent = t.V;
  const double x_max = t.V.col(0).maxCoeff();
  for (Eigen::Index v = 0; v < bent.rows(); ++v)
    if (bent(v, 0) > 0.8 * x_max) bent(v, 2) += 0.1 * (bent(v, 0) - 0.8 * x_max);
  const Proportions p = proportions(t, bent, Eigen::Vector3d::UnitZ());
  EXPECT_LT(p.affine_departure_pct, 1.0);
  EXPECT_GE(p.height_change_pct, 0.0);
}

TEST(Proportions, FoldedFacesAreCountedAsBruteForceCountsThem) {
  const Surface ball = test::icosphere(2);
  Points pushed = ball.V;
  // Push one vertex through the ball's centre: the faces around it turn over.
  const Eigen::RowVector3d centre(0, 0, 10);
  pushed.row(0) = centre - 0.5 * (ball.V.row(0) - centre);
  long expected = 0;
  for (Eigen::Index f = 0; f < ball.F.rows(); ++f) {
    const Eigen::Vector3d a0 = ball.V.row(ball.F(f, 0)), b0 = ball.V.row(ball.F(f, 1)), c0 = ball.V.row(ball.F(f, 2));
    const Eigen::Vector3d a1 = pushed.row(ball.F(f, 0)), b1 = pushed.row(ball.F(f, 1)), c1 = pushed.row(ball.F(f, 2));
    if ((b0 - a0).cross(c0 - a0).dot((b1 - a1).cross(c1 - a1)) < 0) ++expected;
  }
  ASSERT_GT(expected, 0);
  EXPECT_EQ(proportions(ball, pushed, Eigen::Vector3d::UnitZ()).folded_faces, expected);
  EXPECT_EQ(proportions(ball, ball.V, Eigen::Vector3d::UnitZ()).folded_faces, 0);
}

TEST(Proportions, AFlatPartHasNoStretchAcrossItself) {
  // A flat square sheet stretched 2% in x: no extent across the sheet, so the fit leaves that
  // direction alone instead of reading noise there.
  Surface sheet;
  sheet.V.resize(4, 3);
  sheet.V << 0, 0, 0, 10, 0, 0, 10, 10, 0, 0, 10, 0;
  sheet.F.resize(2, 3);
  sheet.F << 0, 1, 2, 0, 2, 3;
  const Proportions p = proportions(sheet, mapped(sheet.V, Eigen::Vector3d(1.02, 1, 1).asDiagonal()), Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(p.affine_departure_pct, 2.0, 1e-9);
  EXPECT_EQ(p.extent_change_pct.z(), 0.0);
  EXPECT_EQ(p.height_change_pct, 0.0);
}

TEST(Proportions, AResultOfAnotherSizeIsRefused) {
  const Surface t = test::t_shape();
  EXPECT_THROW(proportions(t, t.V.topRows(3), Eigen::Vector3d::UnitZ()), std::invalid_argument);
  Points bad = t.V;
  bad(0, 0) = std::nan("");
  EXPECT_THROW(proportions(t, bad, Eigen::Vector3d::UnitZ()), std::invalid_argument);
}

}  // namespace
}  // namespace slim
