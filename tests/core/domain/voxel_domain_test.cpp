#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "core/domain/voxel_domain.h"
#include "core/geometry/surface.h"
#include "support/shapes.h"

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace slim;

namespace {

double diagonal(const Surface& s) { return (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm(); }

// Grid coordinates of a domain vertex, rounded (they are integers up to rounding).
Eigen::Vector3i node_of(const VoxelDomain& dom, Eigen::Index v) {
  const Eigen::Vector3d g = dom.grid.to_grid(dom.mesh.V.row(v).transpose());
  EXPECT_LT((g - g.array().round().matrix()).norm(), 1e-9);
  return g.array().round().cast<int>();
}

bool kept(const VoxelDomain& dom, const Eigen::Vector3i& c) {
  for (int a = 0; a < 3; ++a)
    if (c(a) < 0 || c(a) >= dom.grid.cells(a)) return false;
  return dom.cell_rank[static_cast<size_t>(dom.grid.cell_index(c(0), c(1), c(2)))] >= 0;
}

// Every tet positive; every triangle of the tets shared by at most two tets; a triangle used by
// one tet lies on a cell face whose other cell is not kept (so no neighbour was split differently).
void expect_conforming(const VoxelDomain& dom, const std::string& name) {
  const double h3 = std::pow(dom.grid.cell_size, 3);
  std::map<std::array<int, 3>, std::vector<int>> faces;
  for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t) {
    ASSERT_NEAR(tet_volume(dom.mesh.V, dom.mesh.T.row(t)), h3 / 6.0, 1e-9 * h3) << name << " tet " << t;
    for (int m = 0; m < 4; ++m) {
      std::array<int, 3> f{};
      for (int c = 0, n = 0; c < 4; ++c)
        if (c != m) f[static_cast<size_t>(n++)] = dom.mesh.T(t, c);
      std::sort(f.begin(), f.end());
      faces[f].push_back(static_cast<int>(t));
    }
  }
  size_t boundary = 0;
  for (const auto& [f, tets] : faces) {
    ASSERT_LE(tets.size(), 2u) << name;
    if (tets.size() == 2) continue;
    ++boundary;
    // A boundary triangle is half a cell face: its corners share one grid coordinate.
    const Eigen::Vector3i a = node_of(dom, f[0]), b = node_of(dom, f[1]), c = node_of(dom, f[2]);
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (a(k) == b(k) && b(k) == c(k)) axis = k;
    ASSERT_GE(axis, 0) << name << ": an unshared triangle inside a cell";
    // The tet's own cell (i, j, k): corner 0 of every Kuhn tet is node (i, j, k).
    const Eigen::Vector3i cell = node_of(dom, dom.mesh.T(tets[0], 0));
    Eigen::Vector3i other = cell;
    other(axis) += (a(axis) == cell(axis)) ? -1 : 1;
    EXPECT_FALSE(kept(dom, other)) << name << ": a kept neighbour does not share a boundary triangle";
  }
  EXPECT_GT(boundary, 0u);
}

}  // namespace

TEST(PrintFrame, OrthonormalRightHandedAndIdentityForZ) {
  EXPECT_TRUE(print_frame(Eigen::Vector3d::UnitZ()).isApprox(Eigen::Matrix3d::Identity(), 1e-15));
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 1, 1).normalized(),
                                   Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), Eigen::Vector3d(1, 0, 0)}) {
    const Eigen::Matrix3d F = print_frame(d);
    EXPECT_TRUE((F * F.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-14));
    EXPECT_NEAR(F.determinant(), 1.0, 1e-14);
    EXPECT_TRUE(F.row(2).transpose().isApprox(d, 1e-15));
  }
}

TEST(KuhnSplit, SixPositiveTetsFillTheCube) {
  double volume = 0;
  for (int p = 0; p < 6; ++p) {
    Points V(4, 3);
    for (int m = 0; m < 4; ++m) {
      const int c = kuhn_corners(p)[static_cast<size_t>(m)];
      V.row(m) << (c & 1), (c >> 1) & 1, (c >> 2) & 1;
    }
    const double v = tet_volume(V, Eigen::RowVector4i(0, 1, 2, 3));
    EXPECT_NEAR(v, 1.0 / 6.0, 1e-15);
    volume += v;
    // kuhn_barycentric and kuhn_planes agree and rebuild a point of the tet.
    const Eigen::Vector3d x = V.colwise().mean().transpose();
    const Eigen::Vector4d b = kuhn_barycentric(p, x);
    EXPECT_NEAR(b.sum(), 1.0, 1e-15);
    EXPECT_GT(b.minCoeff(), 0.0);
    EXPECT_LT((V.transpose() * b - x).norm(), 1e-15);
    const TetPlanes P = kuhn_planes(Eigen::Vector3i(3, 1, 2), p);
    for (size_t m = 0; m < 4; ++m)
      EXPECT_NEAR(P.w[m].dot(x + Eigen::Vector3d(3, 1, 2)) + P.o[m], b(static_cast<Eigen::Index>(m)), 1e-14);
  }
  EXPECT_NEAR(volume, 1.0, 1e-15);
}

TEST(VoxelDomain, ConformingPositiveAndOnThePlateForAllShapes) {
  for (const auto& c : test::domain_cases()) {
    SCOPED_TRACE(c.name);
    const VoxelDomain dom = voxel_domain(c.surface, c.print_direction);
    ASSERT_GT(dom.mesh.T.rows(), 0);
    ASSERT_EQ(dom.mesh.T.rows(), static_cast<Eigen::Index>(6 * dom.kept_cells.size()));
    expect_conforming(dom, c.name);

    // Compact: every domain vertex is used by a tet.
    std::vector<bool> used(static_cast<size_t>(dom.mesh.V.rows()), false);
    for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t)
      for (int k = 0; k < 4; ++k) used[static_cast<size_t>(dom.mesh.T(t, k))] = true;
    EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));

    // The plate: the lowest vertex defines it, grid layer 0 lies on it, nothing below it.
    const Eigen::VectorXd height = c.surface.V * c.print_direction;
    const Eigen::VectorXd node_height = dom.mesh.V * c.print_direction;
    EXPECT_EQ(height.minCoeff(), dom.plate_height);
    const double tol = 1e-9 * diagonal(c.surface);
    Eigen::Index plate_nodes = 0;
    for (Eigen::Index v = 0; v < dom.mesh.V.rows(); ++v) {
      EXPECT_GE(node_height(v), dom.plate_height - tol);
      EXPECT_EQ(dom.on_plate(v), std::abs(node_height(v) - dom.plate_height) <= tol) << "vertex " << v;
      plate_nodes += dom.on_plate(v);
    }
    EXPECT_GE(plate_nodes, 4);  // at least one cell face rests on the plate

    // The longest side has exactly `resolution` cells.
    EXPECT_EQ(dom.grid.cells.maxCoeff(), VoxelDomainOptions{}.resolution);
  }
}

TEST(VoxelDomain, EnclosesTheVolumeOfClosedShapes) {
  for (const auto& c : test::domain_cases()) {
    if (!c.closed) continue;
    SCOPED_TRACE(c.name);
    const VoxelDomain dom = voxel_domain(c.surface, c.print_direction);
    double volume = 0;
    for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t) volume += tet_volume(dom.mesh.V, dom.mesh.T.row(t));
    // (The cube's faces lie on grid planes, so there the two volumes agree up to rounding.)
    EXPECT_GE(volume, std::abs(signed_volume(c.surface)) * (1 - 1e-12));
  }
}

// For a sphere of radius r resting on the plate: every cell whose centre lies deeper than
// `inner` cells inside is kept and, when `outer` > 0, none farther than `outer` cells outside.
// Returns the number of deep cells.
int expect_sphere_filled(const VoxelDomain& dom, double r, double inner, double outer) {
  const double h = dom.grid.cell_size;
  int deep = 0;
  for (int k = 0; k < dom.grid.cells(2); ++k)
    for (int j = 0; j < dom.grid.cells(1); ++j)
      for (int i = 0; i < dom.grid.cells(0); ++i) {
        const Eigen::Vector3d centre = dom.grid.to_world(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        const double dist = (centre - Eigen::Vector3d(0, 0, r)).norm();
        if (dist < r - inner * h) {
          EXPECT_TRUE(kept(dom, {i, j, k})) << i << " " << j << " " << k;
          ++deep;
        }
        if (outer > 0 && dist > r + outer * h) {
          EXPECT_FALSE(kept(dom, {i, j, k})) << i << " " << j << " " << k;
        }
      }
  return deep;
}

TEST(VoxelDomain, FillsTheInsideOfASphereAndNothingFarOutside) {
  const double r = 10;
  const VoxelDomain dom = voxel_domain(test::icosphere(4, r, Eigen::Vector3d(0, 0, r)), Eigen::Vector3d::UnitZ());
  EXPECT_GT(expect_sphere_filled(dom, r, 1.0, 1.0), 1000);
  EXPECT_GT(dom.inside_cells, 0);
}

TEST(VoxelDomain, FillsAShellWithAHoleInItsBase) {
  // The sphere without the faces within 20 degrees of its lowest point: every cell well inside
  // is still kept, because only the rays through the hole lose their vote.
  const double r = 10;
  const Surface sphere = test::icosphere(4, r, Eigen::Vector3d(0, 0, r));
  Surface holed = sphere;
  int kept_faces = 0;
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    const double z = (sphere.V(sphere.F(f, 0), 2) + sphere.V(sphere.F(f, 1), 2) + sphere.V(sphere.F(f, 2), 2)) / 3;
    if (z > r * (1 - std::cos(20 * M_PI / 180))) holed.F.row(kept_faces++) = sphere.F.row(f);
  }
  ASSERT_LT(kept_faces, sphere.F.rows());
  holed.F.conservativeResize(kept_faces, 3);
  EXPECT_GT(expect_sphere_filled(voxel_domain(holed, Eigen::Vector3d::UnitZ()), r, 2.0, 0.0), 1000);
}

TEST(VoxelDomain, OpenAndNonManifoldShapesKeepTheirSurfaceCells) {
  // A single triangle: no inside at all, but its cells are kept.
  const Surface tri = test::triangle({0, 0, 0}, {10, 0, 5}, {0, 10, 10});
  const VoxelDomain dom = voxel_domain(tri, Eigen::Vector3d::UnitZ(), {8});
  EXPECT_EQ(dom.inside_cells, 0);
  EXPECT_GT(dom.surface_cells, 8);
  for (Eigen::Index v = 0; v < 3; ++v) {
    const Eigen::Vector3i c = dom.grid.to_grid(tri.V.row(v).transpose())
                                  .array()
                                  .floor()
                                  .cwiseMax(0)
                                  .cwiseMin(dom.grid.cells.cast<double>().array() - 1)
                                  .cast<int>();
    EXPECT_TRUE(kept(dom, c));
  }
}

TEST(VoxelDomain, DefaultResolutionGivesTheBunnyAFewThousandVertices) {
#ifndef SLIM_TESTS_HAVE_VCG
  GTEST_SKIP() << "no VCG to load the bunny";
#else
  const VoxelDomain dom = voxel_domain(test::load_mesh(test::sample_bunny_path()), Eigen::Vector3d::UnitZ());
  EXPECT_GT(dom.mesh.V.rows(), 2000);
  EXPECT_LT(dom.mesh.V.rows(), 8000);
#endif
}

TEST(VoxelDomain, SameResultWhateverTheThreadCount) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  // Big enough for every loop to run in parallel (small ones stay on one thread).
  const Surface s = test::transformed(test::icosphere(5), test::axis_angle({1, 1, 0}, 0.4));
  const Eigen::Vector3d d(0.1, 0.2, 1.0);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const VoxelDomain one = voxel_domain(s, d, {40});
  omp_set_num_threads(std::max(2, threads));
  const VoxelDomain many = voxel_domain(s, d, {40});
  omp_set_num_threads(threads);
  EXPECT_EQ(one.mesh.V, many.mesh.V);
  EXPECT_EQ(one.mesh.T, many.mesh.T);
  EXPECT_EQ(one.kept_cells, many.kept_cells);
#endif
}

TEST(VoxelDomain, MemoryGuardRefusesAnAbsurdResolutionQuickly) {
  const Surface s = test::t_shape();
  const auto start = std::chrono::steady_clock::now();
  try {
    voxel_domain(s, Eigen::Vector3d::UnitZ(), {100000});
    FAIL() << "no exception";
  } catch (const DomainTooLarge& e) {
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(ms, 100.0);
    EXPECT_NE(std::string(e.what()).find("100000"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(std::to_string(e.fitting_resolution)), std::string::npos) << e.what();
    EXPECT_GT(e.cells, 1e12);
    EXPECT_GT(e.bytes, 2e9);
    // The suggested resolution is the largest that fits.
    EXPECT_GT(e.fitting_resolution, 24);
    EXPECT_LE(estimate_voxel_domain(s, Eigen::Vector3d::UnitZ(), e.fitting_resolution).max_bytes, 2e9);
    EXPECT_GT(estimate_voxel_domain(s, Eigen::Vector3d::UnitZ(), e.fitting_resolution + 1).max_bytes, 2e9);
  }
  // A small budget: refused, and the suggested resolution builds within it.
  VoxelDomainOptions small{64};
  small.max_bytes = 2e6;
  try {
    voxel_domain(s, Eigen::Vector3d::UnitZ(), small);
    FAIL() << "no exception";
  } catch (const DomainTooLarge& e) {
    ASSERT_GE(e.fitting_resolution, 1);
    small.resolution = e.fitting_resolution;
    const VoxelDomain dom = voxel_domain(s, Eigen::Vector3d::UnitZ(), small);
    EXPECT_EQ(dom.grid.cells.maxCoeff(), e.fitting_resolution);
    EXPECT_LE(estimate_voxel_domain(s, Eigen::Vector3d::UnitZ(), e.fitting_resolution).max_bytes, 2e6);
  }
  EXPECT_THROW(voxel_domain(s, Eigen::Vector3d::UnitZ(), {100000}), std::invalid_argument);
}

TEST(VoxelDomain, RejectsBadInput) {
  const Surface cube = test::box({0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(voxel_domain(Surface{}, Eigen::Vector3d::UnitZ()), std::invalid_argument);
  Surface point = cube;
  point.V.setConstant(2.0);
  EXPECT_THROW(voxel_domain(point, Eigen::Vector3d::UnitZ()), std::invalid_argument);
  Surface nan = cube;
  nan.V(0, 0) = std::nan("");
  EXPECT_THROW(voxel_domain(nan, Eigen::Vector3d::UnitZ()), std::invalid_argument);
  EXPECT_THROW(voxel_domain(cube, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(voxel_domain(cube, Eigen::Vector3d::UnitZ(), {0}), std::invalid_argument);
  VoxelDomainOptions votes;
  votes.min_inside_votes = 0;
  EXPECT_THROW(voxel_domain(cube, Eigen::Vector3d::UnitZ(), votes), std::invalid_argument);
}
