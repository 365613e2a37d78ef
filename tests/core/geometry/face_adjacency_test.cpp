// Faces across edges (core/geometry/face_adjacency.h): symmetric on closed meshes, -1 where an edge is not
// manifold or its faces disagree on the orientation.
#include <gtest/gtest.h>

#include "core/geometry/face_adjacency.h"
#include "support/shapes.h"

namespace slim {
namespace {

TEST(FaceAdjacency, EveryEdgeOfAClosedMeshHasItsTwin) {
  const Surface s = test::icosphere(2);
  const FaceAdjacency a(s);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const FaceAdjacency::Twin t = a.across(f, k);
      ASSERT_GE(t.face, 0);
      ASSERT_NE(t.face, f);
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      EXPECT_NE(t.opposite, u);
      EXPECT_NE(t.opposite, v);
      int back = -1;  // the twin's edge v -> u points back at f
      for (int m = 0; m < 3; ++m)
        if (s.F(t.face, m) == v && s.F(t.face, (m + 1) % 3) == u) back = a.across(t.face, m).face;
      EXPECT_EQ(back, f);
    }
  }
  int listed = 0;
  for (int v = 0; v < s.V.rows(); ++v) {
    for (const int* f = a.faces_begin(v); f != a.faces_end(v); ++f, ++listed) {
      EXPECT_TRUE(s.F(*f, 0) == v || s.F(*f, 1) == v || s.F(*f, 2) == v);
      if (f != a.faces_begin(v)) {
        EXPECT_LT(f[-1], *f);
      }
    }
  }
  EXPECT_EQ(listed, 3 * s.F.rows());
}

TEST(FaceAdjacency, NoTwinAcrossNonManifoldOrFlippedEdges) {
  const Surface cubes = test::two_cubes_sharing_edge();
  const FaceAdjacency a(cubes);
  int missing = 0;
  for (int f = 0; f < cubes.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) missing += a.across(f, k).face < 0;
  EXPECT_GT(missing, 0);  // the four faces on the shared edge have no single twin
  Surface s = test::icosphere(1);
  std::swap(s.F(0, 1), s.F(0, 2));  // one face turned over
  const FaceAdjacency b(s);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.across(0, k).face, -1);
    EXPECT_EQ(b.across(0, k).opposite, -1);
  }
}

TEST(FaceAdjacency, OpenEdgesHaveNoTwin) {
  const Surface s = test::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const FaceAdjacency a(s);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a.across(0, k).face, -1);
  for (int v = 0; v < 3; ++v) EXPECT_EQ(a.faces_end(v) - a.faces_begin(v), 1);
}


// With every twin found up front (the support model's, kept across iterates), across() answers
// what the search around a vertex answers, on closed, open and non-manifold meshes.
TEST(FaceAdjacency, TheTwinTableAnswersAsTheSearchDoes) {
  for (const Surface& s : {test::refined(test::icosphere(2), 1), test::two_cubes_sharing_edge(1.0),
                           test::refined(test::mushroom(), 1)}) {
    const FaceAdjacency search(s), table(s.F, s.V.rows(), true);
    for (int f = 0; f < s.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(table.across(f, k).face, search.across(f, k).face) << f << " " << k;
        EXPECT_EQ(table.across(f, k).opposite, search.across(f, k).opposite) << f << " " << k;
      }
  }
}

}  // namespace
}  // namespace slim
