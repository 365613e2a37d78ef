// Faces across edges (core/face_adjacency.h): symmetric on closed meshes, -1 where an edge is not
// manifold or its faces disagree on the orientation.
#include <gtest/gtest.h>

#include "core/face_adjacency.h"
#include "support/shapes.h"

namespace slim {
namespace {

TEST(FaceAdjacency, EveryEdgeOfAClosedMeshHasItsTwin) {
  const Surface s = test::icosphere(2);
  const FaceAdjacency a = face_adjacency(s);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int g = a.across[3 * f + k];
      ASSERT_GE(g, 0);
      ASSERT_NE(g, f);
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3), x = a.opposite[3 * f + k];
      EXPECT_NE(x, u);
      EXPECT_NE(x, v);
      int back = -1;  // g's edge v -> u points back at f
      for (int m = 0; m < 3; ++m)
        if (s.F(g, m) == v && s.F(g, (m + 1) % 3) == u) back = a.across[3 * g + m];
      EXPECT_EQ(back, f);
    }
  }
  for (int v = 0; v < s.V.rows(); ++v) {
    for (int i = a.vertex_begin[v]; i < a.vertex_begin[v + 1]; ++i) {
      const int f = a.vertex_face[i];
      EXPECT_TRUE(s.F(f, 0) == v || s.F(f, 1) == v || s.F(f, 2) == v);
      if (i > a.vertex_begin[v]) {
        EXPECT_LT(a.vertex_face[i - 1], f);
      }
    }
  }
}

TEST(FaceAdjacency, NoTwinAcrossNonManifoldOrFlippedEdges) {
  const Surface cubes = test::two_cubes_sharing_edge();
  const FaceAdjacency a = face_adjacency(cubes);
  int missing = 0;
  for (int e = 0; e < 3 * cubes.F.rows(); ++e) missing += a.across[e] < 0;
  EXPECT_GT(missing, 0);  // the four faces on the shared edge have no single twin
  Surface s = test::icosphere(1);
  std::swap(s.F(0, 1), s.F(0, 2));  // one face turned over
  const FaceAdjacency b = face_adjacency(s);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.across[k], -1);
    EXPECT_EQ(b.opposite[k], -1);
  }
}

TEST(FaceAdjacency, OpenEdgesHaveNoTwin) {
  const Surface s = test::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const FaceAdjacency a = face_adjacency(s);
  EXPECT_EQ(a.across, std::vector<int>({-1, -1, -1}));
  EXPECT_EQ(a.vertex_face, std::vector<int>({0, 0, 0}));
}

}  // namespace
}  // namespace slim
