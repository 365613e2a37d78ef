#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "core/domain/embedding.h"
#include "core/domain/voxel_domain.h"
#include "core/geometry/surface.h"
#include "support/shapes.h"
#include "support/tet_grid.h"

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace slim;

namespace {

double diagonal(const Points& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// The invariants every embedding must satisfy, whatever the domain.
void expect_valid(const Surface& s, const TetMesh& dom, const Embedding& e, const std::string& name) {
  SCOPED_TRACE(name);
  const Eigen::Index nv = s.V.rows(), nf = s.F.rows(), nt = dom.T.rows();
  const double tol = 1e-9 * diagonal(s.V);
  ASSERT_EQ(e.vertex_tet.size(), nv);
  for (Eigen::Index i = 0; i < nv; ++i) {
    const int t = e.vertex_tet(i);
    ASSERT_TRUE(t >= 0 && t < nt);
    EXPECT_EQ(e.vertex_nodes.row(i), dom.T.row(t));
    EXPECT_NEAR(e.vertex_bary.row(i).sum(), 1.0, 1e-12) << "vertex " << i;
    EXPECT_GE(e.vertex_bary.row(i).minCoeff(), -1e-9) << "vertex " << i;
    Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) p += e.vertex_bary(i, k) * dom.V.row(dom.T(t, k));
    EXPECT_LE((p - s.V.row(i)).norm(), tol) << "vertex " << i;
  }
  // The precomputed rebuild is the identity on the undeformed domain.
  Points rebuilt;
  embedded_positions(e, dom.V, rebuilt);
  EXPECT_LE((rebuilt - s.V).rowwise().norm().maxCoeff(), tol);

  // CSR shape, faces ascending within a tet, and each face's pieces sum to its area.
  ASSERT_EQ(e.tet_face_offsets.size(), nt + 1);
  ASSERT_EQ(e.tet_face_offsets(0), 0);
  ASSERT_EQ(e.tet_face_offsets(nt), e.tet_faces.size());
  ASSERT_EQ(e.tet_face_areas.size(), e.tet_faces.size());
  Eigen::VectorXd covered = Eigen::VectorXd::Zero(nf);
  for (Eigen::Index t = 0; t < nt; ++t) {
    ASSERT_LE(e.tet_face_offsets(t), e.tet_face_offsets(t + 1));
    for (int p = e.tet_face_offsets(t); p < e.tet_face_offsets(t + 1); ++p) {
      if (p > e.tet_face_offsets(t)) {
        EXPECT_LT(e.tet_faces(p - 1), e.tet_faces(p));
      }
      ASSERT_TRUE(e.tet_faces(p) >= 0 && e.tet_faces(p) < nf);
      EXPECT_GE(e.tet_face_areas(p), 0.0);
      covered(e.tet_faces(p)) += e.tet_face_areas(p);
    }
  }
  const Eigen::VectorXd area = face_areas(s);
  for (Eigen::Index f = 0; f < nf; ++f) EXPECT_NEAR(covered(f), area(f), 1e-6 * area(f)) << "face " << f;
}

// Tets that hold a piece of some face.
size_t tets_with_faces(const Embedding& e) {
  size_t n = 0;
  for (Eigen::Index t = 0; t + 1 < e.tet_face_offsets.size(); ++t) n += e.tet_face_offsets(t + 1) > e.tet_face_offsets(t);
  return n;
}

}  // namespace

TEST(Embedding, VoxelDomainInvariantsForAllShapes) {
  for (const auto& c : test::domain_cases()) {
    const VoxelDomain dom = voxel_domain(c.surface, c.print_direction);
    expect_valid(c.surface, dom.mesh, embed_surface(c.surface, dom), c.name);
  }
}

TEST(Embedding, GeneralTetMeshPathGivesTheSameInvariants) {
  // The bucket search (used for TetGen domains) on the voxel domain's plain TetMesh.
  for (const auto& c : test::domain_cases()) {
    const VoxelDomain dom = voxel_domain(c.surface, c.print_direction, {12});
    const Embedding general = embed_surface(c.surface, dom.mesh);
    expect_valid(c.surface, dom.mesh, general, c.name + " (general)");
    // Both searches pick a tet whose smallest coordinate is as large as possible.
    const Embedding grid = embed_surface(c.surface, dom);
    for (Eigen::Index i = 0; i < c.surface.V.rows(); ++i)
      EXPECT_NEAR(general.vertex_bary.row(i).minCoeff(), grid.vertex_bary.row(i).minCoeff(), 1e-9);
  }
}

TEST(Embedding, FollowsAnAffineDeformationOfTheDomain) {
  const Surface s = test::t_shape();
  const VoxelDomain dom = voxel_domain(s, Eigen::Vector3d::UnitZ(), {16});
  const Embedding e = embed_surface(s, dom);
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0.0, -0.1, 0.9, 0.3, 0.05, 0.0, 1.2;
  const Eigen::RowVector3d shift(1, -2, 3);
  const Points moved = (dom.mesh.V * A.transpose()).rowwise() + shift;
  Points surface;
  embedded_positions(e, moved, surface);
  const Points expected = (s.V * A.transpose()).rowwise() + shift;
  EXPECT_LE((surface - expected).rowwise().norm().maxCoeff(), 1e-9 * diagonal(s.V));
}

TEST(Embedding, CoarseFacesAreSplitOverEveryTetTheyCross) {
  // A cube of 12 triangles on a 24-cell grid: each triangle crosses hundreds of tets, and its
  // faces lie on grid planes, where a face must go to exactly one side.
  const Surface s = test::box({0, 0, 0}, {10, 20, 30});
  const VoxelDomain dom = voxel_domain(s, Eigen::Vector3d::UnitZ());
  const Embedding clipped = embed_surface(s, dom);
  expect_valid(s, dom.mesh, clipped, "cube");
  EXPECT_EQ(clipped.split_faces, 12);
  EXPECT_GT(tets_with_faces(clipped), 500u);
  // Every piece went to a tet inside the cube (its back side), none to the outside layer.
  for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t) {
    if (clipped.tet_face_offsets(t + 1) == clipped.tet_face_offsets(t)) continue;
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) centre += dom.mesh.V.row(dom.mesh.T(t, k)) / 4.0;
    EXPECT_TRUE((centre.array() > 0).all() && (centre.array() < Eigen::Array3d(10, 20, 30).transpose()).all());
  }

  // The centroid fallback: one piece per face, so only 12 tets see the surface.
  EmbeddingOptions centroid;
  centroid.faces = FaceAssignment::centroid;
  const Embedding coarse = embed_surface(s, dom, centroid);
  expect_valid(s, dom.mesh, coarse, "cube by centroid");
  EXPECT_EQ(coarse.tet_faces.size(), 12);
  EXPECT_LE(tets_with_faces(coarse), 12u);
}

TEST(Embedding, PiecesMatchAnIndependentAreaSplit) {
  // A single slanted triangle over a 4-cell grid: the area inside each cell column, summed over
  // the column's tets, equals the area of the triangle clipped to that column, computed here
  // from the triangle's parametrisation by fine sampling.
  const Surface tri = test::triangle({0.1, 0.2, 0.0}, {3.7, 0.4, 1.3}, {1.2, 3.9, 2.6});
  const VoxelDomain dom = voxel_domain(tri, Eigen::Vector3d::UnitZ(), {4});
  const Embedding e = embed_surface(tri, dom);
  expect_valid(tri, dom.mesh, e, "triangle");
  std::map<std::pair<int, int>, double> by_column;
  for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t)
    for (int p = e.tet_face_offsets(t); p < e.tet_face_offsets(t + 1); ++p) {
      const std::int64_t cell = dom.kept_cells[static_cast<size_t>(t / 6)];
      const int i = static_cast<int>(cell % dom.grid.cells(0)), j = static_cast<int>((cell / dom.grid.cells(0)) % dom.grid.cells(1));
      by_column[{i, j}] += e.tet_face_areas(p);
    }
  const int n = 800;
  const double area = face_areas(tri)(0);
  std::map<std::pair<int, int>, double> sampled;
  for (int a = 0; a < n; ++a)
    for (int b = 0; a + b < n; ++b) {
      const double u = (a + 1.0 / 3) / n, v = (b + 1.0 / 3) / n;
      const Eigen::Vector3d x = ((1 - u - v) * tri.V.row(0) + u * tri.V.row(1) + v * tri.V.row(2)).transpose();
      const Eigen::Vector3d g = dom.grid.to_grid(x);
      sampled[{static_cast<int>(g(0)), static_cast<int>(g(1))}] += area / (0.5 * n * (n + 1));
    }
  for (const auto& [column, a] : sampled) EXPECT_NEAR(by_column[column], a, 0.01 * area);
}

TEST(Embedding, RefusesAVertexOutsideAGeneralDomain) {
  TetMesh one;
  one.V.resize(4, 3);
  one.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  one.T.resize(1, 4);
  one.T << 0, 1, 2, 3;
  const Surface s = test::triangle({0.1, 0.1, 0.1}, {0.2, 0.1, 0.1}, {0.9, 0.9, 0.9});
  try {
    embed_surface(s, one);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
  }
}

TEST(Embedding, SameResultWhateverTheThreadCount) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  // Big enough for every loop to run in parallel (small ones stay on one thread).
  const Surface s = test::transformed(test::icosphere(5), test::axis_angle({1, 2, 0}, 0.3));
  const VoxelDomain dom = voxel_domain(s, Eigen::Vector3d::UnitZ(), {40});
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Embedding one = embed_surface(s, dom);
  omp_set_num_threads(std::max(2, threads));
  const Embedding many = embed_surface(s, dom);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.vertex_tet, many.vertex_tet);
  EXPECT_EQ(one.vertex_bary, many.vertex_bary);
  EXPECT_EQ(one.tet_face_offsets, many.tet_face_offsets);
  EXPECT_EQ(one.tet_faces, many.tet_faces);
  EXPECT_EQ(one.tet_face_areas, many.tet_face_areas);
#endif
}

TEST(Embedding, GeneralTetMeshPathLocatesPointsInsideIrregularTets) {
  // The general path's barycentric coordinates on tets that are not Kuhn tets of a grid: a
  // jittered tet grid, and a cloud of points strictly inside it. Every point must be rebuilt from
  // its coordinates in the tet it was given, and that tet must hold it (all coordinates >= 0).
  TetMesh m = test::tet_grid(3, 3, 3, 10.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-2.0, 2.0), inside(1.0, 29.0);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const bool boundary = (m.V.row(v).array() == 0.0).any() || (m.V.row(v).array() == 30.0).any();
    if (!boundary) m.V.row(v) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
  }
  for (Eigen::Index t = 0; t < m.T.rows(); ++t) ASSERT_GT(tet_volume(m.V, m.T.row(t)), 0.0);
  Surface cloud;
  cloud.V.resize(300, 3);
  for (Eigen::Index i = 0; i < cloud.V.rows(); ++i) cloud.V.row(i) << inside(rng), inside(rng), inside(rng);
  cloud.F.resize(100, 3);
  for (Eigen::Index f = 0; f < 100; ++f) cloud.F.row(f) << static_cast<int>(3 * f), static_cast<int>(3 * f + 1), static_cast<int>(3 * f + 2);
  const Embedding e = embed_surface(cloud, m);
  Points rebuilt;
  embedded_positions(e, m.V, rebuilt);
  EXPECT_LT((rebuilt - cloud.V).rowwise().norm().maxCoeff(), 1e-9);
  for (Eigen::Index i = 0; i < cloud.V.rows(); ++i) {
    EXPECT_GE(e.vertex_bary.row(i).minCoeff(), -1e-9) << "point " << i;
  }
}
