#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "core/domain/embedding.h"
#include "core/domain/tetgen_domain.h"
#include "core/geometry/surface.h"
#include "support/shapes.h"

using namespace slim;

namespace {

std::string refusal(const Surface& s) {
  try {
    check_tetgen_input(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool mentions(const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; }

}  // namespace

TEST(TetgenInputCheck, AcceptsCleanClosedMeshes) {
  EXPECT_EQ(refusal(test::box({0, 0, 0}, {1, 2, 3})), "");
  EXPECT_EQ(refusal(test::icosphere(3)), "");
  EXPECT_EQ(refusal(test::t_shape()), "");
}

TEST(TetgenInputCheck, NamesWhatIsWrong) {
  EXPECT_TRUE(mentions(refusal(test::open_hemisphere(2)), "not closed"));
  EXPECT_TRUE(mentions(refusal(test::two_cubes_sharing_edge()), "not manifold"));
  Surface flipped = test::box({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.F(0, 1), flipped.F(0, 2));
  EXPECT_TRUE(mentions(refusal(flipped), "not consistently oriented"));
  Surface degenerate = test::box({0, 0, 0}, {1, 1, 1});
  degenerate.F(3, 2) = degenerate.F(3, 1);
  EXPECT_TRUE(mentions(refusal(degenerate), "zero area"));
  // Two overlapping boxes, and two boxes touching face to face (unwelded): both intersect.
  const std::string overlap = refusal(test::merge(test::box({0, 0, 0}, {2, 2, 2}), test::box({1, 1, 1}, {3, 3, 3})));
  EXPECT_TRUE(mentions(overlap, "intersects itself")) << overlap;
  const std::string touch = refusal(test::merge(test::box({0, 0, 0}, {1, 1, 1}), test::box({1, 0, 0}, {2, 1, 1})));
  EXPECT_TRUE(mentions(touch, "intersects itself")) << touch;
  // A nested box does not touch: fine for the check (TetGen makes a cavity-free solid of both).
  EXPECT_EQ(refusal(test::merge(test::box({0, 0, 0}, {3, 3, 3}), test::box({1, 1, 1}, {2, 2, 2}))), "");
}

TEST(TetgenInputCheck, FindsFoldsAndOverlappingFans) {
  // A flattened tetrahedron: faces sharing an edge fold onto each other.
  Surface flat;
  flat.V.resize(4, 3);
  flat.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 1;
  flat.F.resize(4, 3);
  flat.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3;
  EXPECT_EQ(refusal(flat), "");
  flat.V(3, 2) = 0.0;
  EXPECT_TRUE(mentions(refusal(flat), "intersects itself"));

  // Two tetrahedra sharing one vertex (a bow tie): fine when they point away from each other,
  // wrong when the second one is turned into the first.
  auto bow_tie = [](double second_height, double turn) {
    Surface s;
    s.V.resize(7, 3);
    s.V.row(0) << 0, 0, 0;
    for (int k = 0; k < 3; ++k) {
      const double a = 2 * M_PI * k / 3, b = a + turn;
      s.V.row(1 + k) << std::cos(a), std::sin(a), 1;
      s.V.row(4 + k) << std::cos(b), std::sin(b), second_height;
    }
    s.F.resize(8, 3);
    s.F << 0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3,  // apex down, base on top: outward
        0, 5, 4, 0, 6, 5, 0, 4, 6, 4, 5, 6;
    if (second_height < 0)
      for (Eigen::Index f = 4; f < 8; ++f) std::swap(s.F(f, 1), s.F(f, 2));
    return s;
  };
  EXPECT_EQ(refusal(bow_tie(-1.0, 0.3)), "");
  EXPECT_TRUE(mentions(refusal(bow_tie(2.0, M_PI / 3)), "intersects itself"));

  // A sphere with one vertex pulled through the far side: its fan pierces other faces.
  Surface spike = test::icosphere(2);
  Eigen::Index top = 0;
  spike.V.col(2).maxCoeff(&top);
  spike.V(top, 2) = -5;
  EXPECT_TRUE(mentions(refusal(spike), "intersects itself"));
}

TEST(TetgenDomain, TetrahedralizesCleanClosedMeshes) {
  if (!tetgen_available()) {
    EXPECT_THROW(tetgen_domain(test::box({0, 0, 0}, {1, 1, 1}), Eigen::Vector3d::UnitZ()), std::runtime_error);
    GTEST_SKIP() << "built without TetGen";
  }
  for (const Surface& s : {test::icosphere(2), test::box({0, 0, 0}, {10, 20, 30}), test::t_shape()}) {
    const TetgenDomain dom = tetgen_domain(s, Eigen::Vector3d::UnitZ());
    ASSERT_GT(dom.mesh.T.rows(), 0);
    double volume = 0;
    for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t) {
      const double v = tet_volume(dom.mesh.V, dom.mesh.T.row(t));
      EXPECT_GT(v, 0.0);
      volume += v;
    }
    // The tets fill exactly the solid: the surface is kept ("Y").
    EXPECT_NEAR(volume, signed_volume(s), 1e-9 * signed_volume(s));
    for (Eigen::Index v = 0; v < s.V.rows(); ++v)
      EXPECT_EQ(dom.mesh.V.row(dom.surface_vertex(v)), s.V.row(v));
    EXPECT_EQ(dom.plate_height, s.V.col(2).minCoeff());
    const double diag = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm();
    for (Eigen::Index v = 0; v < dom.mesh.V.rows(); ++v)
      EXPECT_EQ(dom.on_plate(v), dom.mesh.V(v, 2) <= dom.plate_height + 1e-9 * diag);

    // The general embedding: surface vertices sit on domain vertices, faces split by area.
    const Embedding e = embed_surface(s, dom.mesh);
    const Eigen::VectorXd area = face_areas(s);
    Eigen::VectorXd covered = Eigen::VectorXd::Zero(s.F.rows());
    for (Eigen::Index p = 0; p < e.tet_faces.size(); ++p) covered(e.tet_faces(p)) += e.tet_face_areas(p);
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) EXPECT_NEAR(covered(f), area(f), 1e-6 * area(f));
    // "Y" keeps every surface triangle a tet face, so no face is split.
    EXPECT_EQ(e.split_faces, 0);
    for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
      EXPECT_NEAR(e.vertex_bary.row(v).maxCoeff(), 1.0, 1e-9);
      EXPECT_GE(e.vertex_bary.row(v).minCoeff(), -1e-9);
    }
  }
}

TEST(TetgenDomain, RefusesASelfIntersectingMeshWithoutCrashing) {
  const Surface s = test::merge(test::box({0, 0, 0}, {2, 2, 2}), test::box({1, 1, 1}, {3, 3, 3}));
  if (!tetgen_available()) GTEST_SKIP() << "built without TetGen";
  EXPECT_THROW(tetgen_domain(s, Eigen::Vector3d::UnitZ()), std::invalid_argument);
}

TEST(TetgenDomain, ACrashingChildIsAnError) {
  if (!tetgen_available()) GTEST_SKIP() << "built without TetGen";
  TetgenOptions o;
  o.test_fault = TetgenChildFault::crash;
  try {
    tetgen_domain(test::box({0, 0, 0}, {1, 1, 1}), Eigen::Vector3d::UnitZ(), o);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(mentions(e.what(), "crashed")) << e.what();
  }
  // And the next call in the same process still works.
  EXPECT_GT(tetgen_domain(test::box({0, 0, 0}, {1, 1, 1}), Eigen::Vector3d::UnitZ()).mesh.T.rows(), 0);
}

TEST(TetgenDomain, AHangingChildIsStoppedByTheTimeout) {
  if (!tetgen_available()) GTEST_SKIP() << "built without TetGen";
  TetgenOptions o;
  o.test_fault = TetgenChildFault::hang;
  o.timeout_seconds = 0.3;
  const auto start = std::chrono::steady_clock::now();
  try {
    tetgen_domain(test::box({0, 0, 0}, {1, 1, 1}), Eigen::Vector3d::UnitZ(), o);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(mentions(e.what(), "did not finish")) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(TetgenDomain, AChildOutOfMemoryIsAnError) {
  if (!tetgen_available()) GTEST_SKIP() << "built without TetGen";
  TetgenOptions o;
  o.child_memory_bytes = 1e5;  // TetGen's pools need far more
  try {
    tetgen_domain(test::icosphere(3), Eigen::Vector3d::UnitZ(), o);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(mentions(e.what(), "memory")) << e.what();
  }
}

TEST(TetgenDomain, RejectsBadOptions) {
  if (!tetgen_available()) GTEST_SKIP() << "built without TetGen";
  const Surface cube = test::box({0, 0, 0}, {1, 1, 1});
  TetgenOptions o;
  o.timeout_seconds = 0;
  EXPECT_THROW(tetgen_domain(cube, Eigen::Vector3d::UnitZ(), o), std::invalid_argument);
  o = {};
  o.max_tet_volume = -1;
  EXPECT_THROW(tetgen_domain(cube, Eigen::Vector3d::UnitZ(), o), std::invalid_argument);
  EXPECT_THROW(tetgen_domain(cube, Eigen::Vector3d::Zero()), std::invalid_argument);
}
