// core/geometry/surface_distance.h: the closest point on a triangle against a dense sampling of it, the
// grid search against a scan of every face, and known distances.
#include <gtest/gtest.h>

#include <random>

#include "core/geometry/closest_on_triangle.h"
#include "core/geometry/surface_distance.h"
#include "support/shapes.h"

using namespace slim;

namespace {

// The distance from q to the nearest of n*(n+1)/2 points spread over the triangle.
double sampled_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c, int n) {
  double best = HUGE_VAL;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, (a + u * (b - a) + v * (c - a) - q).norm());
    }
  return best;
}

}  // namespace

TEST(SurfaceDistance, ClosestPointOnATriangleIsNoFartherThanAnyOfItsPoints) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d a(g(rng), g(rng), g(rng)), b(g(rng), g(rng), g(rng));
    Eigen::Vector3d c(g(rng), g(rng), g(rng));
    if (trial % 10 == 0) c = a + 0.3 * (b - a);  // collinear: a flat triangle
    const Eigen::Vector3d q(2 * g(rng), 2 * g(rng), 2 * g(rng));
    const Eigen::Vector3d x = closest_on_triangle(q, a, b, c);
    const double exact = (x - q).norm(), sampled = sampled_distance(q, a, b, c, 200);
    EXPECT_LE(exact, sampled + 1e-12) << trial;
    EXPECT_GE(exact, sampled - 0.02 * (b - a).norm() - 0.02 * (c - a).norm()) << trial;  // and on it
  }
}

TEST(SurfaceDistance, TheSearchEqualsAScanOfEveryFace) {
  const Surface a = test::refined(test::t_shape(), 2);
  Surface b = test::transformed(a, test::axis_angle(Eigen::Vector3d(1, 2, 3).normalized(), 0.2), Eigen::Vector3d(1, -2, 0.5));
  const SurfaceDistance d = surface_distance(a, b);
  // The scan: every vertex of a against every face of b (the vertices are among the samples).
  double scan = 0.0;
  for (Eigen::Index v = 0; v < a.V.rows(); ++v) {
    double best = HUGE_VAL;
    for (Eigen::Index f = 0; f < b.F.rows(); ++f)
      best = std::min(best, (closest_on_triangle(a.V.row(v).transpose(), b.V.row(b.F(f, 0)).transpose(), b.V.row(b.F(f, 1)).transpose(),
                                                 b.V.row(b.F(f, 2)).transpose()) - a.V.row(v).transpose()).norm());
    scan = std::max(scan, best);
  }
  EXPECT_GE(d.a_to_b_max_mm, scan - 1e-12);
  EXPECT_GT(d.a_to_b_max_mm, 0.5);
}

TEST(SurfaceDistance, KnownDistances) {
  const Surface s = test::icosphere(4, 10.0);
  EXPECT_NEAR(surface_distance(s, s).hausdorff_mm, 0.0, 1e-12);
  // A box and the same box moved up by 2: the farthest point of each is 2 from the other.
  const Surface box = test::box({0, 0, 0}, {10, 10, 10});
  const Surface up = test::transformed(box, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 2));
  const SurfaceDistance d = surface_distance(box, up);
  EXPECT_NEAR(d.hausdorff_mm, 2.0, 1e-12);
  EXPECT_NEAR(d.a_to_b_max_mm, 2.0, 1e-12);
  EXPECT_GT(d.a_to_b_mean_mm, 0.0);
  EXPECT_LT(d.a_to_b_mean_mm, 2.0);
  // A sphere and one 3% larger about the same centre: 0.3 apart everywhere (to the faceting).
  const Surface big = test::transformed(s, 1.03 * Eigen::Matrix3d::Identity(), -0.03 * Eigen::Vector3d(0, 0, 10));
  EXPECT_NEAR(surface_distance(s, big).hausdorff_mm, 0.3, 0.02);
}

// The figures' Hausdorff distance of a mesh and its moved copy searches only the samples that moved
// most: the same value as the full search, on smooth and rough motions, large and small.
TEST(SurfaceDistance, MovedMeshSearchEqualsTheFullSearch) {
  const Surface ball = test::icosphere(3, 10.0);
  std::mt19937 gen(5);
  std::normal_distribution<double> g;
  for (double amount : {0.0, 0.05, 0.5, 3.0}) {
    Surface moved = ball;
    for (Eigen::Index v = 0; v < ball.V.rows(); ++v) {
      const double bulge = std::max(0.0, ball.V(v, 2) - 12.0);  // a smooth dent on one side
      moved.V.row(v) += amount * (bulge * Eigen::RowVector3d(0.3, 0, -1) + 0.1 * Eigen::RowVector3d(g(gen), g(gen), g(gen)));
    }
    // Unmoved, the full search finds the rounding of the closest points (1e-15); the moved search none.
    EXPECT_NEAR(hausdorff_of_moved(ball, moved), surface_distance(ball, moved).hausdorff_mm, amount > 0 ? 0.0 : 1e-12)
        << amount;
  }
  const Surface box = test::box({0, 0, 0}, {10, 10, 10});
  EXPECT_DOUBLE_EQ(hausdorff_of_moved(box, test::transformed(box, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 2))), 2.0);
  EXPECT_THROW(hausdorff_of_moved(ball, test::icosphere(2, 10.0)), std::invalid_argument);
}

// A ball turned 5 degrees about its axis, with a bump near the pole: the points that moved most
// (the equator's, 0.87 mm along the surface) lie on it to the faceting, and the bump (0.3 mm out,
// where the turn moves little) holds the distance. The search must go past its first block of
// 4096 vertices and faces, to the rest that moved further than the distance found there.
TEST(SurfaceDistance, MovedMeshSearchGoesOnPastThePointsThatMovedMost) {
  const Surface ball = test::icosphere(5, 10.0, Eigen::Vector3d::Zero());  // 10,242 vertices, 20,480 faces
  Surface moved = test::transformed(ball, test::axis_angle(Eigen::Vector3d::UnitZ(), 5.0 * M_PI / 180.0));
  for (Eigen::Index v = 0; v < ball.V.rows(); ++v) {
    const double cap = std::max(0.0, ball.V(v, 2) - 9.5) / 0.5;  // 0 below z = 9.5, 1 at the pole
    moved.V.row(v) *= 1.0 + 0.03 * cap;
  }
  const double full = surface_distance(ball, moved).hausdorff_mm;
  EXPECT_GT(full, 0.25);  // the bump's, not the turn's
  EXPECT_EQ(hausdorff_of_moved(ball, moved), full);
  EXPECT_EQ(hausdorff_of_moved(moved, ball), full);
}

// A vertex that no face uses is no part of the surface: it changes neither distance, however far
// from the surface it lies or moves (the moved search would otherwise bound it by its move alone).
TEST(SurfaceDistance, AVertexOfNoFaceIsNoSample) {
  const Surface box = test::box({0, 0, 0}, {10, 10, 10});
  const Surface up = test::transformed(box, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 2));
  Surface box_stray = box, up_stray = up;
  box_stray.V.conservativeResize(box.V.rows() + 1, 3);
  up_stray.V.conservativeResize(up.V.rows() + 1, 3);
  box_stray.V.row(box.V.rows()) = Eigen::RowVector3d(0, 0, 100);  // 90 mm above both boxes
  up_stray.V.row(up.V.rows()) = Eigen::RowVector3d(0, 0, 100.5);
  EXPECT_NEAR(surface_distance(box_stray, up_stray).hausdorff_mm, 2.0, 1e-12);
  EXPECT_NEAR(surface_distance(box_stray, up).hausdorff_mm, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(hausdorff_of_moved(box_stray, up_stray), 2.0);
  EXPECT_EQ(surface_distance(box_stray, up_stray).a_to_b_mean_mm, surface_distance(box, up).a_to_b_mean_mm);
}
