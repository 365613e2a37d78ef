// The distance from a point to a surface through the tree of face boxes (core/geometry/face_box_tree.h)
// against a scan of every face: the same distance to the bit and the same face (ties: the lower),
// for points near the surface, far outside it and on its vertices (where faces tie), on a bumpy
// ball, a T with long thin faces, a surface with faces of no area, and none; and on a ball large
// enough for the tree to be built in parallel, on one thread and on two; and a tree refit to the
// same faces moved far from where it split them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/closest_on_triangle.h"
#include "core/geometry/face_box_tree.h"
#include "core/geometry/surface_distance.h"
#include "core/platform/parallel_for.h"
#include "support/shapes.h"

using namespace slim;

namespace {

double scan(const Surface& s, const Eigen::Vector3d& p, int& face) {
  double best = HUGE_VAL;
  face = -1;
  for (int f = 0; f < static_cast<int>(s.F.rows()); ++f) {
    const double d = (closest_on_triangle(p, s.V.row(s.F(f, 0)).transpose(), s.V.row(s.F(f, 1)).transpose(),
                                          s.V.row(s.F(f, 2)).transpose()) - p).norm();
    if (face < 0 || d < best) best = d, face = f;
  }
  return best;
}

}  // namespace

TEST(FaceBoxTree, TheDistanceAndFaceAreAScansToTheBit) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> bump(-0.2, 0.2), near(-12.0, 12.0), far(-80.0, 80.0);
  Surface ball = test::icosphere(4);
  for (Eigen::Index v = 0; v < ball.V.rows(); ++v) ball.V.row(v) *= 1.0 + 0.05 * bump(gen);
  Surface squashed = test::refined(test::t_shape(), 1);
  for (Eigen::Index f = 0; f < squashed.F.rows(); f += 7) squashed.V.row(squashed.F(f, 1)) = squashed.V.row(squashed.F(f, 0));
  for (const Surface& s : {ball, test::t_shape(), squashed}) {
    const FaceBoxTree tree(s);
    for (int q = 0; q < 900; ++q) {
      const Eigen::Vector3d p = q < 300   ? Eigen::Vector3d(near(gen), near(gen), 10.0 + near(gen))
                                : q < 600 ? Eigen::Vector3d(far(gen), far(gen), far(gen))
                                          : Eigen::Vector3d(s.V.row(q % s.V.rows()).transpose());
      int expected_face = -1, face = -2;
      const double expected = scan(s, p, expected_face);
      EXPECT_EQ(tree.distance(p, &face), expected) << p.transpose();
      EXPECT_EQ(face, expected_face) << p.transpose();
    }
  }
  int face = 0;
  EXPECT_EQ(FaceBoxTree(Surface{}).distance(Eigen::Vector3d::Zero(), &face), HUGE_VAL);
  EXPECT_EQ(face, -1);
}

TEST(FaceBoxTree, ALargeSurfaceBuiltOnAnyThreadCountGivesAScansDistance) {
  // 81,920 faces: the tree's subtrees of 16,384 faces and more are built as OpenMP tasks.
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> bump(-0.2, 0.2), near(-12.0, 12.0);
  Surface ball = test::icosphere(6);
  for (Eigen::Index v = 0; v < ball.V.rows(); ++v) ball.V.row(v) *= 1.0 + 0.05 * bump(gen);
  ASSERT_GE(ball.F.rows(), 65536);
  std::vector<Eigen::Vector3d> points;
  std::vector<double> expected;
  std::vector<int> expected_face;
  for (int q = 0; q < 150; ++q) {
    points.emplace_back(near(gen), near(gen), 10.0 + near(gen));
    expected_face.push_back(-1);
    expected.push_back(scan(ball, points.back(), expected_face.back()));
  }
  for (int threads : {1, 2}) {
    const ThreadScope scope(threads);
    const FaceBoxTree tree(ball);
    for (size_t q = 0; q < points.size(); ++q) {
      int face = -2;
      EXPECT_EQ(tree.distance(points[q], &face), expected[q]) << threads << " threads, " << points[q].transpose();
      EXPECT_EQ(face, expected_face[q]) << threads << " threads, " << points[q].transpose();
    }
  }
}

// A bumpy ball's tree refit to the ball twisted by up to 90 degrees about Z and stretched: its
// leaves keep faces that now lie far apart, and every answer is still the scan's.
TEST(FaceBoxTree, ARefitTreeOfTheFacesMovedGivesAScansDistance) {
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> bump(-0.2, 0.2), near(-15.0, 15.0);
  Surface ball = test::icosphere(4);
  for (Eigen::Index v = 0; v < ball.V.rows(); ++v) ball.V.row(v) *= 1.0 + 0.05 * bump(gen);
  Surface moved = ball;
  for (Eigen::Index v = 0; v < ball.V.rows(); ++v) {
    const double z = ball.V(v, 2), turn = M_PI / 2 * z / 20.0;
    moved.V.row(v) = Eigen::RowVector3d(std::cos(turn) * ball.V(v, 0) - std::sin(turn) * ball.V(v, 1),
                                        std::sin(turn) * ball.V(v, 0) + std::cos(turn) * ball.V(v, 1), 1.5 * z);
  }
  const FaceBoxTree tree(ball);
  const FaceBoxTree refit(tree, moved);
  for (int q = 0; q < 600; ++q) {
    const Eigen::Vector3d p = q < 400 ? Eigen::Vector3d(near(gen), near(gen), 15.0 + 2.0 * near(gen))
                                      : Eigen::Vector3d(moved.V.row(q % moved.V.rows()).transpose());
    int expected_face = -1, face = -2;
    const double expected = scan(moved, p, expected_face);
    EXPECT_EQ(refit.distance(p, &face), expected) << p.transpose();
    EXPECT_EQ(face, expected_face) << p.transpose();
  }
}
