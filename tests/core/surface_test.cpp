#include <gtest/gtest.h>

#include <map>

#include "core/surface.h"
#include "support/shapes.h"

using namespace slim;

TEST(Shapes, ClosedShapesAreOutwardAndHaveTheirVolume) {
  EXPECT_NEAR(signed_volume(test::box({0, 0, 0}, {1, 2, 3})), 6.0, 1e-12);
  const test::TShape p;
  const double t_volume = p.stem * p.stem * p.height + p.bar_length * p.stem * p.bar_thickness;
  EXPECT_NEAR(signed_volume(test::t_shape(p)), t_volume, 1e-9);
  const double r = 10.0;
  EXPECT_NEAR(signed_volume(test::icosphere(4, r)), 4.0 / 3.0 * M_PI * r * r * r, 0.01 * 4188.8);
}

TEST(Shapes, TwoCubesShareOneEdge) {
  const Surface s = test::two_cubes_sharing_edge(1.0);
  EXPECT_EQ(s.V.rows(), 14);  // 16 corners, two welded
  EXPECT_NEAR(signed_volume(s), 2.0, 1e-12);
}

TEST(Surface, NormalsAndAreasOfABox) {
  const Surface s = test::box({0, 0, 0}, {2, 3, 4});
  const Points n = face_normals(s);
  const Eigen::VectorXd a = face_areas(s);
  EXPECT_NEAR(a.sum(), 2 * (2 * 3 + 3 * 4 + 2 * 4), 1e-12);
  // Every normal points away from the box centre.
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::RowVector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    EXPECT_GT(n.row(f).dot(c - Eigen::RowVector3d(1, 1.5, 2)), 0.0);
  }
}

TEST(Surface, DegenerateFaceHasZeroNormalAndArea) {
  Surface s;
  s.V.resize(3, 3);
  s.V << 0, 0, 0, 1, 1, 1, 2, 2, 2;
  s.F.resize(1, 3);
  s.F << 0, 1, 2;
  EXPECT_EQ(face_normals(s).row(0).norm(), 0.0);
  EXPECT_EQ(face_areas(s)(0), 0.0);
}

TEST(Surface, CheckRejectsBadIndicesAndNaN) {
  Surface s = test::box({0, 0, 0}, {1, 1, 1});
  s.F(3, 1) = 99;
  EXPECT_THROW(check_surface(s), std::invalid_argument);
  s = test::box({0, 0, 0}, {1, 1, 1});
  s.V(2, 2) = std::nan("");
  EXPECT_THROW(check_surface(s), std::invalid_argument);
}

#ifdef SLIM_TESTS_HAVE_VCG
TEST(SampleBunny, LoadsStandingOnThePlate) {
  const Surface s = test::load_mesh(test::sample_bunny_path());
  EXPECT_EQ(s.V.rows(), 1839);
  EXPECT_GT(s.F.rows(), 3000);
  EXPECT_NEAR(s.V.col(2).minCoeff(), 0.0, 1e-5);
  // +Z up: the bunny is taller than it is deep (Y), which was its height in the npm data.
  const Eigen::RowVector3d extent = s.V.colwise().maxCoeff() - s.V.colwise().minCoeff();
  EXPECT_GT(extent(2), extent(1));
  EXPECT_GT(signed_volume(s), 0.0);
}
#endif

TEST(Shapes, MushroomAndArchAreClosedOutwardAndOverhang) {
  for (const Surface& s : {test::mushroom(), test::arch()}) {
    EXPECT_GT(signed_volume(s), 0.0);
    // Closed: every directed edge appears once and its reverse once.
    std::map<std::pair<int, int>, int> edges;
    for (Eigen::Index f = 0; f < s.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) ++edges[{s.F(f, k), s.F(f, (k + 1) % 3)}];
    for (const auto& [e, count] : edges) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(edges.count({e.second, e.first}), 1u);
    }
    EXPECT_NEAR(s.V.col(2).minCoeff(), 0.0, 1e-12);
  }
  // The arch's volume: the 30 x 20 block minus the opening (a 20 x 8 rectangle and a half disc).
  const double arch_area = 30 * 20 - (20 * 8 + 0.5 * M_PI * 100 * (std::sin(M_PI / 24) * 24 / M_PI));
  EXPECT_NEAR(signed_volume(test::arch()), 10 * arch_area, 1e-6);
}
