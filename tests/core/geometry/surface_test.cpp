#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/geometry/surface.h"
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

namespace slim {
namespace {

// edge_topology against a plain map of every edge's faces, on a mesh with each kind of flaw: a
// hole (faces removed), an edge of three faces (a face repeated), faces turned over, a face
// naming a vertex twice (left out), faces in scrambled order.
TEST(Surface, EdgeTopologyCountsAndNamesAsAPlainMapDoes) {
  Surface s = test::merge(test::refined(test::box({0, 0, 0}, {1, 1, 1}), 2), test::icosphere(2, 1.0, {3, 0, 0}));
  std::mt19937 rng(11);
  for (Eigen::Index f = s.F.rows() - 1; f > 0; --f) {  // scrambled order
    const Eigen::Index g = static_cast<Eigen::Index>(rng() % static_cast<unsigned>(f + 1));
    const Eigen::RowVector3i keep = s.F.row(f);
    s.F.row(f) = s.F.row(g);
    s.F.row(g) = keep;
  }
  Triangles F(s.F.rows() + 2, 3);
  F.topRows(s.F.rows()) = s.F;
  F.row(s.F.rows()) = s.F.row(7);                                    // an edge of three faces (and more)
  F.row(s.F.rows() + 1) << s.F(3, 0), s.F(3, 0), s.F(3, 1);           // names a vertex twice
  std::swap(F(20, 1), F(20, 2));                                      // turned over
  std::swap(F(45, 1), F(45, 2));
  Surface flawed{s.V, Triangles(F.rows() - 2, 3)};
  for (Eigen::Index f = 0, k = 0; f < F.rows(); ++f)
    if (f != 100 && f != 101) flawed.F.row(k++) = F.row(f);          // a hole
  const EdgeTopology t = edge_topology(flawed);

  std::map<std::pair<int, int>, std::vector<std::pair<bool, int>>> edges;  // sorted by (lo, hi)
  for (Eigen::Index f = 0; f < flawed.F.rows(); ++f) {
    const Eigen::RowVector3i v = flawed.F.row(f);
    if (v(0) == v(1) || v(1) == v(2) || v(2) == v(0)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = v(k), b = v((k + 1) % 3);
      edges[{std::min(a, b), std::max(a, b)}].push_back({a < b, static_cast<int>(f)});
    }
  }
  EdgeTopology ref;
  for (auto& [edge, faces] : edges) {
    std::sort(faces.begin(), faces.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
    const std::string name = "(" + std::to_string(edge.first) + ", " + std::to_string(edge.second) + ")";
    if (faces.size() == 1 && ref.open_edges++ == 0) ref.first_open = name;
    if (faces.size() > 2 && ref.nonmanifold_edges++ == 0)
      ref.first_nonmanifold = name + " is shared by " + std::to_string(faces.size()) + " faces";
    if (faces.size() == 2 && faces[0].first == faces[1].first && ref.flipped_edges++ == 0)
      ref.first_flipped = "faces " + std::to_string(faces[0].second) + " and " + std::to_string(faces[1].second) +
                          " run along edge " + name + " in the same direction";
  }
  EXPECT_GT(ref.open_edges, 0);
  EXPECT_GT(ref.nonmanifold_edges, 0);
  EXPECT_GT(ref.flipped_edges, 0);
  EXPECT_EQ(t.open_edges, ref.open_edges);
  EXPECT_EQ(t.nonmanifold_edges, ref.nonmanifold_edges);
  EXPECT_EQ(t.flipped_edges, ref.flipped_edges);
  EXPECT_EQ(t.first_open, ref.first_open);
  EXPECT_EQ(t.first_nonmanifold, ref.first_nonmanifold);
  EXPECT_EQ(t.first_flipped, ref.first_flipped);
}

}  // namespace
}  // namespace slim
