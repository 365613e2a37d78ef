// The constraints that hold the part's proportions (core/optimizer/rigid_proportions.h) and the
// surface guards (core/optimizer/surface_guards.h), on a ball embedded in its voxel domain: any domain
// motion within the constraints leaves the best-fit affine map free of stretch, by an independent
// least-squares fit and by proportions.h; a stretch breaks them; the fold guard finds exactly the
// tets of the faces turned past 90 degrees, and rolling them back leaves none.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "core/domain/embedded_domain.h"
#include "core/geometry/checked_surface.h"
#include "core/geometry/proportions.h"
#include "core/optimizer/surface_guards.h"
#include "core/optimizer/rigid_proportions.h"
#include "core/optimizer/step_guards.h"
#include "support/shapes.h"

using namespace slim;

namespace {

struct BallInDomain {
  Surface ball = test::icosphere(3);
  EmbeddedDomain domain = embedded_domain(CheckedSurface(ball), Eigen::Vector3d::UnitZ(), DomainKind::Voxel, 10, 4e9,
                                          [](double, const std::string&) {});
  Points surface(const Points& P) const {
    Points S(ball.V.rows(), 3);
    embedded_positions(domain.embedding, P, S);
    return S;
  }
};

Points random_motion(Eigen::Index rows, double size, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> n(0.0, size);
  return Points::NullaryExpr(rows, 3, [&]() { return n(gen); });
}

// B of the best-fit affine map X -> Y (least squares about the centroid, dense and independent).
Eigen::Matrix3d affine_linear_part_minus_identity(const Points& X, const Points& Y) {
  const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
  const Eigen::MatrixXd D = (Y - X).rowwise() - (Y - X).colwise().mean();
  return Xc.colPivHouseholderQr().solve(D);  // 3 by 3, Y - X ~ Xc B
}

double stretch(const Eigen::Matrix3d& B) { return (0.5 * (B + B.transpose())).cwiseAbs().maxCoeff(); }

// dV minus its component against the constraints (dense least squares on the stacked unknowns).
Points within(const std::vector<Points>& C, const Points& dV) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(C.size()), dV.size());
  for (size_t k = 0; k < C.size(); ++k) A.row(static_cast<Eigen::Index>(k)) = C[k].reshaped().transpose();
  const Eigen::VectorXd x = dV.reshaped();
  const Eigen::VectorXd y = x - A.transpose() * (A * A.transpose()).ldlt().solve(A * x);
  return y.reshaped(dV.rows(), 3);
}

}  // namespace

TEST(RigidProportions, AMotionWithinTheConstraintsAddsNoStretch) {
  const BallInDomain f;
  const Points& V0 = f.domain.mesh.V;
  const std::vector<Points> C = stretch_constraints(f.ball, f.domain.embedding, V0.rows());
  ASSERT_EQ(C.size(), 6u);
  for (unsigned seed : {1u, 2u, 3u}) {
    const Points dV = random_motion(V0.rows(), 0.3, seed);
    const Eigen::Matrix3d free = affine_linear_part_minus_identity(f.ball.V, f.surface(V0 + dV));
    const Points held = V0 + within(C, dV);
    EXPECT_LE((constraint_values(C, held) - constraint_values(C, V0)).cwiseAbs().maxCoeff(), 1e-9);
    const Eigen::Matrix3d B = affine_linear_part_minus_identity(f.ball.V, f.surface(held));
    ASSERT_GT(stretch(free), 1e-3) << "the random motion should stretch the ball";
    EXPECT_LE(stretch(B), 1e-10) << seed;
    // proportions.h reads the same: a departure from rigid of second order only (|B|^2).
    EXPECT_LE(proportions(f.ball, f.surface(held), Eigen::Vector3d::UnitZ()).affine_departure_pct,
              100.0 * B.squaredNorm() + 1e-9);
  }
}

TEST(RigidProportions, AStretchBreaksThemAndATranslationKeepsThem) {
  const BallInDomain f;
  const Points& V0 = f.domain.mesh.V;
  const std::vector<Points> C = stretch_constraints(f.ball, f.domain.embedding, V0.rows());
  const Eigen::VectorXd rest = constraint_values(C, V0);
  Points taller = V0;
  taller.col(2) *= 1.02;
  EXPECT_GT((constraint_values(C, taller) - rest).cwiseAbs().maxCoeff(), 1e-3);
  const Points moved = V0.rowwise() + Eigen::RowVector3d(3.0, -2.0, 5.0);
  EXPECT_LE((constraint_values(C, moved) - rest).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(FoldGuard, FindsTheTetsOfExactlyTheFoldedFacesAndRollingThemBackUnfolds) {
  const BallInDomain f;
  const Points& V0 = f.domain.mesh.V;
  EXPECT_TRUE(folding_tets(f.ball, f.domain.embedding, V0).empty());
  // The upper half of the domain squashed below its middle: the upper faces turn over.
  Points P = V0;
  const double mid = 0.5 * (V0.col(2).minCoeff() + V0.col(2).maxCoeff());
  for (Eigen::Index v = 0; v < P.rows(); ++v)
    if (P(v, 2) > mid) P(v, 2) = mid - 0.5 * (P(v, 2) - mid);
  const Points S = f.surface(P);
  std::vector<int> expected;
  long folded = 0;
  for (Eigen::Index t = 0; t < f.ball.F.rows(); ++t) {
    const Eigen::Vector3d a = face_cross(f.ball.V, f.ball.F, t), b = face_cross(S, f.ball.F, t);
    if (a.dot(b) >= 0.0) continue;
    ++folded;
    for (int k = 0; k < 3; ++k) expected.push_back(f.domain.embedding.vertex_tet(f.ball.F(t, k)));
  }
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  ASSERT_GT(folded, 10);
  EXPECT_EQ(proportions(f.ball, S, Eigen::Vector3d::UnitZ()).folded_faces, folded);
  const std::vector<int> found = folding_tets(f.ball, f.domain.embedding, P);
  EXPECT_EQ(found, expected);
  // Rolled back towards the unfolded rest, the step keeps what did not fold and folds nothing.
  Points proposed = P;
  int held = 0;
  auto folding = [&](const Points& Q) { return folding_tets(f.ball, f.domain.embedding, Q); };
  const std::vector<int> group(static_cast<size_t>(V0.rows()), -1);
  EXPECT_TRUE(roll_back_until(V0, proposed, f.domain.mesh.T, group, found, folding, held));
  EXPECT_TRUE(folding(proposed).empty());
  EXPECT_EQ(proportions(f.ball, f.surface(proposed), Eigen::Vector3d::UnitZ()).folded_faces, 0);
  EXPECT_GT(held, 0);
  EXPECT_LT(held, V0.rows());
}

// The top's allowance: the domain lifted by 1 mm raises every surface vertex by 1 mm, and the
// guard lists exactly the tets of the vertices that end above the input's top plus the allowance.
TEST(SurfaceGuards, FindTheTetsOfTheVerticesAboveTheTopsAllowance) {
  const BallInDomain f;
  const Points& V0 = f.domain.mesh.V;
  const Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  const SurfaceGuards guards(f.ball, f.domain.embedding, d, 2.0);
  const double top = f.ball.V.col(2).maxCoeff(), height = top - f.ball.V.col(2).minCoeff();
  EXPECT_NEAR(guards.ceiling().value(), top + 0.02 * height, 1e-12);
  EXPECT_TRUE(guards.faulty_tets(V0).empty());
  const Points lifted = V0.rowwise() + Eigen::RowVector3d(0.0, 0.0, 1.0);
  const Points S = f.surface(lifted);
  std::vector<int> expected;
  for (Eigen::Index v = 0; v < S.rows(); ++v)
    if (S(v, 2) > top + 0.02 * height) expected.push_back(f.domain.embedding.vertex_tet(v));
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(guards.faulty_tets(lifted), expected);
  EXPECT_TRUE(folding_tets(f.ball, f.domain.embedding, lifted).empty());  // a lift folds nothing
  EXPECT_FALSE(SurfaceGuards(f.ball, f.domain.embedding, d, std::nullopt).ceiling());
  EXPECT_TRUE(SurfaceGuards(f.ball, f.domain.embedding, d, std::nullopt).faulty_tets(lifted).empty());
}
