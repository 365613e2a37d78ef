// The global step's springs and constraints (core/solver/arap.h: anchors, set_constraints): the
// anchored solve is the minimiser of the energy with its springs, checked against an independent
// gradient; anchors hold a part that nothing pins; the constrained solve holds its constraints and
// is the constrained minimiser (its gradient lies in the constraints' span); a load's response
// stays within them.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/solver/arap.h"
#include "support/arap_reference.h"
#include "support/tet_grid.h"

using namespace slim;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr int kNx = 4, kNy = 3, kNz = 5;
TetMesh small_grid() { return test::tet_grid(kNx, kNy, kNz, 2.0, Vector3d(1.0, -3.0, 0.5)); }
std::vector<int> plate() { return test::grid_bottom_vertices(kNx, kNy); }
Eigen::VectorXd weights(const TetMesh& m) {
  Eigen::VectorXd w(m.T.rows());
  for (int t = 0; t < m.T.rows(); ++t) w(t) = tet_volume(m.V, m.T.row(t));
  return w;
}

std::vector<Matrix3d> random_rotations(int count, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  std::vector<Matrix3d> L;
  for (int t = 0; t < count; ++t)
    L.push_back(Eigen::AngleAxisd(u(gen), Vector3d(n(gen), n(gen), n(gen)).normalized()).toRotationMatrix());
  return L;
}

// Springs on the upper half of the grid, of random stiffness; none on the lower half.
Eigen::VectorXd upper_anchors(const TetMesh& m, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(0.1, 5.0);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(m.V.rows());
  const double mid = 0.5 * (m.V.col(2).minCoeff() + m.V.col(2).maxCoeff());
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (m.V(v, 2) > mid) a(v) = u(gen);
  return a;
}

// The rows of the free vertices of a #V by 3 matrix, stacked into one column.
Eigen::VectorXd free_stack(const Points& g, const std::vector<int>& free) {
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(free.size()));
  for (size_t f = 0; f < free.size(); ++f) out.segment<3>(3 * static_cast<Eigen::Index>(f)) = g.row(free[f]).transpose();
  return out;
}

// Random constraints: each #V by 3 with random entries.
std::vector<Points> random_constraints(Eigen::Index nv, int count, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> n;
  std::vector<Points> C;
  for (int k = 0; k < count; ++k) C.push_back(Points::NullaryExpr(nv, 3, [&]() { return n(gen); }));
  return C;
}

Eigen::VectorXd values(const std::vector<Points>& C, const Points& V) {
  Eigen::VectorXd c(static_cast<Eigen::Index>(C.size()));
  for (size_t k = 0; k < C.size(); ++k) c(static_cast<Eigen::Index>(k)) = C[k].cwiseProduct(V).sum();
  return c;
}

}  // namespace

TEST(ArapAnchors, TheAnchoredSolveMinimisesTheEnergyWithItsSprings) {
  const TetMesh m = small_grid();
  const Eigen::VectorXd a = upper_anchors(m, 1);
  const ArapSolver s(m, weights(m), plate(), a);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 2);
  const Points V = s.solve(L, m.V);
  const double g0 = free_stack(test::arap_energy_gradient(m, m.V, L, a), s.free_vertices()).cwiseAbs().maxCoeff();
  ASSERT_GT(g0, 1.0);
  EXPECT_LE(free_stack(test::arap_energy_gradient(m, V, L, a), s.free_vertices()).cwiseAbs().maxCoeff(), 1e-10 * g0);
  // energy() counts the springs: its central differences are the independent gradient.
  const Points g = test::arap_energy_gradient(m, m.V, L, a);
  for (int v : {77, 99, 119}) {
    ASSERT_GT(a(v), 0.0);
    for (int c = 0; c < 3; ++c) {
      Points plus = m.V, minus = m.V;
      plus(v, c) += 1e-5;
      minus(v, c) -= 1e-5;
      EXPECT_NEAR((s.energy(plus, L) - s.energy(minus, L)) / 2e-5, g(v, c), 1e-6 * (1.0 + std::abs(g(v, c))));
    }
  }
  // The springs change the answer: without them the upper half moves further from its rest.
  const Points unanchored = ArapSolver(m, weights(m), plate()).solve(L, m.V);
  double with = 0.0, without = 0.0;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (a(v) > 0.0) with += (V.row(v) - m.V.row(v)).squaredNorm(), without += (unanchored.row(v) - m.V.row(v)).squaredNorm();
  EXPECT_LT(with, 0.9 * without);
}

// Nothing pinned, no anchoring of floating components: a spring is enough to determine the part.
TEST(ArapAnchors, ASpringHoldsAPartThatNothingPins) {
  const TetMesh m = small_grid();
  EXPECT_THROW(ArapSolver(m, weights(m), {}), std::invalid_argument);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(m.V.rows());
  a(7) = 0.5;
  const ArapSolver s(m, weights(m), {}, a);
  EXPECT_TRUE(s.held_vertices().empty());
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 3);
  const Points V = s.solve(L, m.V);
  const double g0 = test::arap_energy_gradient(m, m.V, L, a).cwiseAbs().maxCoeff();
  EXPECT_LE(test::arap_energy_gradient(m, V, L, a).cwiseAbs().maxCoeff(), 1e-9 * g0);
  // The identity leaves the part where it is.
  const std::vector<Matrix3d> I(static_cast<size_t>(m.T.rows()), Matrix3d::Identity());
  EXPECT_LE((s.solve(I, m.V) - m.V).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ArapAnchors, ConstraintsAreHeldByTheConstrainedMinimiser) {
  const TetMesh m = small_grid();
  const Eigen::VectorXd a = upper_anchors(m, 4);
  ArapSolver s(m, weights(m), plate(), a);
  const std::vector<Points> C = random_constraints(m.V.rows(), 5, 5);
  Eigen::VectorXd c = values(C, m.V);
  c(0) += 3.0;  // one that the rest shape does not hold
  s.set_constraints(C, c);
  EXPECT_EQ(s.factorizations(), 1);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 6);
  Points held = m.V;
  for (int v : plate()) held.row(v) += Eigen::RowVector3d(0.1, -0.2, 0.0);  // held rows count with V_held
  const Points V = s.solve(L, held);
  EXPECT_LE((values(C, V) - c).cwiseAbs().maxCoeff(), 1e-9);
  for (int v : plate()) EXPECT_EQ(V.row(v), held.row(v));
  // Lagrange: the gradient on the free rows is a combination of the constraints' free rows.
  const Eigen::VectorXd g = free_stack(test::arap_energy_gradient(m, V, L, a), s.free_vertices());
  Eigen::MatrixXd span(g.size(), static_cast<Eigen::Index>(C.size()));
  for (size_t k = 0; k < C.size(); ++k) span.col(static_cast<Eigen::Index>(k)) = free_stack(C[k], s.free_vertices());
  const Eigen::VectorXd mu = span.colPivHouseholderQr().solve(g);
  ASSERT_GT(g.norm(), 1e-3) << "the constraints should bind";
  EXPECT_LE((span * mu - g).norm(), 1e-9 * g.norm());
  // A load's response stays within them, alone and in solve_with_response (same values).
  Points load(m.V.rows(), 3);
  for (Eigen::Index k = 0; k < load.size(); ++k) load.data()[k] = std::sin(0.37 * static_cast<double>(k + 1));
  const Points u = s.response(load);
  EXPECT_LE(values(C, u).cwiseAbs().maxCoeff(), 1e-9);
  Points u2;
  const Points V2 = s.solve_with_response(L, held, load, u2);
  EXPECT_LE((V2 - V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((u2 - u).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ArapAnchors, BadSpringsAndConstraintsAreRefused) {
  const TetMesh m = small_grid();
  EXPECT_THROW(ArapSolver(m, weights(m), plate(), Eigen::VectorXd::Ones(3)), std::invalid_argument);
  Eigen::VectorXd a = Eigen::VectorXd::Ones(m.V.rows());
  a(4) = -1.0;
  EXPECT_THROW(ArapSolver(m, weights(m), plate(), a), std::invalid_argument);
  a(4) = NAN;
  EXPECT_THROW(ArapSolver(m, weights(m), plate(), a), std::invalid_argument);
  ArapSolver s(m, weights(m), plate(), Eigen::VectorXd());  // empty: no springs
  EXPECT_THROW(s.set_constraints({Points::Zero(3, 3)}, Eigen::VectorXd::Zero(1)), std::invalid_argument);
  EXPECT_THROW(s.set_constraints({Points::Zero(m.V.rows(), 3)}, Eigen::VectorXd::Zero(2)), std::invalid_argument);
}
