// The column under each face: known answers on boxes and the T, and the grid's answer against a
// scan of every face along the line, on a scan turned to an arbitrary print direction.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry/surface.h"
#include "core/print/face_columns.h"
#include "core/print/overhang.h"
#include "support/shapes.h"

using namespace slim;

namespace {

std::vector<bool> all_faces(const Surface& s) { return std::vector<bool>(static_cast<size_t>(s.F.rows()), true); }

// Faces whose unit normal points straight down (-Z).
std::vector<bool> facing_down(const Surface& s) {
  const Points n = face_normals(s);
  std::vector<bool> down(static_cast<size_t>(s.F.rows()));
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) down[static_cast<size_t>(f)] = n(f, 2) < -0.999;
  return down;
}

Eigen::Vector3d centroid(const Surface& s, Eigen::Index f) {
  return (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))).transpose() / 3.0;
}

// Moller-Trumbore along -d from p: the distance to the nearest crossing of any face but `self`,
// else to the plane of the lowest vertex. Every face is tried.
double scanned_column(const Surface& s, Eigen::Index self, const Eigen::Vector3d& d) {
  const Eigen::Vector3d p = centroid(s, self), dir = -d;
  const double plate = (s.V * d).minCoeff();
  double best = p.dot(d) - plate;
  for (Eigen::Index g = 0; g < s.F.rows(); ++g) {
    if (g == self) continue;
    const Eigen::Vector3d a = s.V.row(s.F(g, 0)), b = s.V.row(s.F(g, 1)), c = s.V.row(s.F(g, 2));
    const Eigen::Vector3d e1 = b - a, e2 = c - a, q = dir.cross(e2);
    const double det = e1.dot(q);
    if (std::abs(det) < 1e-15) continue;
    const Eigen::Vector3d r = p - a;
    const double u = r.dot(q) / det, v = dir.dot(r.cross(e1)) / det, t = e2.dot(r.cross(e1)) / det;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0) best = std::min(best, t);
  }
  return std::max(0.0, best);
}

}  // namespace

TEST(FaceColumns, AFloatingBoxHangsItsWholeHeightAboveThePlate) {
  const Surface s = test::merge(test::box({0, 0, 0}, {2, 2, 1}), test::box({10, 0, 7}, {14, 4, 9}));
  const std::vector<bool> down = facing_down(s);
  const Eigen::VectorXd h = column_heights(s, Eigen::Vector3d::UnitZ(), down);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const double expected = !down[static_cast<size_t>(f)] ? 0.0 : centroid(s, f).z();
    EXPECT_NEAR(h(f), expected, 1e-12) << "face " << f;
  }
}

TEST(FaceColumns, ALedgeOverThePartStandsOnThePartBelow) {
  // A block on the plate, and two boxes above it at z 8: one over the block (its column lands on
  // the block's top at z 4) and one beyond it (down to the plate).
  const Surface s = test::merge(test::box({0, 0, 0}, {10, 10, 4}),
                                test::merge(test::box({0, 0, 8}, {10, 10, 12}), test::box({10, 0, 8}, {20, 10, 12})));
  const std::vector<bool> down = facing_down(s);
  const Eigen::VectorXd h = column_heights(s, Eigen::Vector3d::UnitZ(), down);
  int over_block = 0, beyond = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (!down[static_cast<size_t>(f)] || centroid(s, f).z() < 1.0) continue;
    if (centroid(s, f).x() < 10.0) {
      EXPECT_NEAR(h(f), 4.0, 1e-12);
      ++over_block;
    } else {
      EXPECT_NEAR(h(f), 8.0, 1e-12);
      ++beyond;
    }
  }
  EXPECT_EQ(over_block, 2);
  EXPECT_EQ(beyond, 2);
}

TEST(FaceColumns, TheTsArmsHangAtTheStemsHeight) {
  const test::TShape p;
  const Surface s = test::t_shape(p);
  const OverhangReport r = analyse_overhang(s);
  const Eigen::VectorXd h = column_heights(s, Eigen::Vector3d::UnitZ(), r.risky);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    EXPECT_NEAR(h(f), r.risky[static_cast<size_t>(f)] ? p.height : 0.0, 1e-12) << "face " << f;
}

TEST(FaceColumns, TheGridFindsWhatAScanOfEveryFaceFinds) {
  // A scan in an arbitrary pose: every face's column against a scan of all faces along its line.
  const Eigen::Vector3d d = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Surface s = test::transformed(test::sample_bunny(), test::axis_angle({1, 2, 3}, 0.7), {5, -3, 2});
  const Eigen::VectorXd h = column_heights(s, d, all_faces(s));
  const double plate = (s.V * d).minCoeff();
  int over_part = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const double scanned = scanned_column(s, f, d);
    ASSERT_NEAR(h(f), scanned, 1e-9 * (1.0 + scanned)) << "face " << f;
    if (h(f) < centroid(s, f).dot(d) - plate - 1e-6) ++over_part;
  }
  EXPECT_GT(over_part, s.F.rows() / 4);  // the part below carries many of the lines
}

TEST(FaceColumns, OnlyTheFlaggedFacesAreMeasured) {
  const Surface s = test::t_shape();
  std::vector<bool> none(static_cast<size_t>(s.F.rows()), false);
  EXPECT_EQ(column_heights(s, Eigen::Vector3d::UnitZ(), none).cwiseAbs().maxCoeff(), 0.0);
}
