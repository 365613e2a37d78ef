// Quickhull: every point inside, a closed triangulated sphere (Euler), known answers.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

#include "core/geometry/convex_hull.h"
#include "support/shapes.h"

using namespace slim;

namespace {

// Every point on or inside every facet's plane; every facet edge shared by exactly two facets,
// each the other's neighbour across it; V - E + F = 2.
void expect_closed_convex(const Points& P, const ConvexHull& hull, double eps) {
  ASSERT_EQ(hull.neighbours.size(), hull.facets.size());
  for (size_t f = 0; f < hull.facets.size(); ++f) {
    const Eigen::Vector3d n = hull.normals.row(static_cast<Eigen::Index>(f)).transpose();
    const double offset = n.dot(P.row(hull.facets[f][0]).transpose());
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    EXPECT_LE((P * n).maxCoeff() - offset, 2 * eps) << "facet " << f;
  }
  std::map<std::pair<int, int>, int> directed;
  for (size_t f = 0; f < hull.facets.size(); ++f)
    for (int e = 0; e < 3; ++e) ++directed[{hull.facets[f][static_cast<size_t>(e)], hull.facets[f][static_cast<size_t>((e + 1) % 3)]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  for (size_t f = 0; f < hull.facets.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int g = hull.neighbours[f][static_cast<size_t>(e)];
      ASSERT_GE(g, 0);
      bool back = false;
      for (int k = 0; k < 3; ++k) back = back || hull.neighbours[static_cast<size_t>(g)][static_cast<size_t>(k)] == static_cast<int>(f);
      EXPECT_TRUE(back);
    }
  const long v = static_cast<long>(hull.vertices.size()), e = static_cast<long>(directed.size()) / 2,
             faces = static_cast<long>(hull.facets.size());
  EXPECT_EQ(v - e + faces, 2);
}

}  // namespace

TEST(ConvexHull, RandomPointsAreAllInside) {
  std::mt19937_64 gen(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Points P(2000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) P.row(i) << u(gen), u(gen), u(gen);
  ConvexHull hull;
  ASSERT_TRUE(convex_hull(P, 1e-12, hull));
  expect_closed_convex(P, hull, 1e-12);
}

TEST(ConvexHull, TessellatedBoxKeepsOnlyItsCorners) {
  // Refined, each side holds many coplanar points: they are on the hull, not vertices of it.
  const Surface box = test::refined(test::box({0, 0, 0}, {10, 20, 30}), 3);
  ConvexHull hull;
  ASSERT_TRUE(convex_hull(box.V, 1e-9, hull));
  expect_closed_convex(box.V, hull, 1e-9);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.facets.size(), 12u);
  EXPECT_NEAR(hull.areas.sum(), 2 * (10 * 20 + 20 * 30 + 10 * 30), 1e-9);
}

TEST(ConvexHull, SphereUsesEveryPoint) {
  const Surface sphere = test::icosphere(3);
  ConvexHull hull;
  ASSERT_TRUE(convex_hull(sphere.V, 1e-9, hull));
  expect_closed_convex(sphere.V, hull, 1e-9);
  EXPECT_EQ(hull.vertices.size(), static_cast<size_t>(sphere.V.rows()));
}

TEST(ConvexHull, FlatOrTinyInputHasNoHull) {
  ConvexHull hull;
  Points square(4, 3);
  square << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  EXPECT_FALSE(convex_hull(square, 1e-9, hull));
  EXPECT_TRUE(hull.facets.empty());
  EXPECT_FALSE(convex_hull(square.topRows(3), 1e-9, hull));
  Points bad = square;
  bad(0, 2) = std::nan("");
  EXPECT_FALSE(convex_hull(bad, 1e-9, hull));
}
