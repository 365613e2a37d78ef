// Linear equality constraints on a factored least-squares solve (core/solver/linear_constraints.h)
// against the brute force: the full KKT system [K C^T; C 0] solved densely, on random symmetric
// positive definite systems, with dependent constraints and with a load's response.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/solver/linear_constraints.h"

using namespace slim;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

struct System {
  MatrixXd K;  // n by n, symmetric positive definite
  MatrixXd b;  // n by k
  std::vector<MatrixXd> C;  // m of n by k
  VectorXd c;  // m
};

System random_system(int n, int k, int m, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g;
  auto random = [&](int rows, int cols) { return MatrixXd::NullaryExpr(rows, cols, [&]() { return g(gen); }).eval(); };
  System s;
  const MatrixXd A = random(n, n);
  s.K = A * A.transpose() + n * MatrixXd::Identity(n, n);
  s.b = random(n, k);
  for (int j = 0; j < m; ++j) s.C.push_back(random(n, k));
  s.c = random(m, 1);
  return s;
}

// The minimiser of sum over columns of 1/2 x^T K x - b^T x under <C_j, x> = c_j, from the full
// KKT system on the n k unknowns stacked column by column.
MatrixXd kkt_solution(const System& s) {
  const int n = static_cast<int>(s.K.rows()), k = static_cast<int>(s.b.cols()), m = static_cast<int>(s.C.size());
  MatrixXd A = MatrixXd::Zero(n * k + m, n * k + m);
  VectorXd r = VectorXd::Zero(n * k + m);
  for (int col = 0; col < k; ++col) {
    A.block(col * n, col * n, n, n) = s.K;
    r.segment(col * n, n) = s.b.col(col);
  }
  for (int j = 0; j < m; ++j) {
    const VectorXd stacked = s.C[static_cast<size_t>(j)].reshaped();
    A.block(n * k + j, 0, 1, n * k) = stacked.transpose();
    A.block(0, n * k + j, n * k, 1) = stacked;
    r(n * k + j) = s.c(j);
  }
  const VectorXd x = A.fullPivLu().solve(r);
  return x.head(n * k).reshaped(n, k);
}

}  // namespace

TEST(LinearConstraints, TheProjectedSolveIsTheConstrainedMinimiser) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const System s = random_system(40, 3, 6, seed);
    const Eigen::LDLT<MatrixXd> K(s.K);
    const LinearConstraints cons(s.C, [&](const MatrixXd& rhs) { return K.solve(rhs).eval(); });
    MatrixXd x = K.solve(s.b);
    ASSERT_GT((cons.values(x) - s.c).norm(), 1e-3) << "the free minimiser should not hold the constraints";
    cons.project(x, s.c);
    EXPECT_LE((cons.values(x) - s.c).cwiseAbs().maxCoeff(), 1e-10) << seed;
    EXPECT_LE((x - kkt_solution(s)).cwiseAbs().maxCoeff(), 1e-10) << seed;
  }
}

// A constraint that repeats another (or combines others) adds nothing and must not blow up.
TEST(LinearConstraints, DependentConstraintsAreHeldAsFarAsTheOthersHoldThem) {
  System s = random_system(30, 3, 3, 7);
  s.C.push_back(2.0 * s.C[0] - s.C[1]);
  s.c.conservativeResize(4);
  s.c(3) = 2.0 * s.c(0) - s.c(1);  // consistent
  const Eigen::LDLT<MatrixXd> K(s.K);
  const LinearConstraints cons(s.C, [&](const MatrixXd& rhs) { return K.solve(rhs).eval(); });
  MatrixXd x = K.solve(s.b);
  cons.project(x, s.c);
  EXPECT_LE((cons.values(x) - s.c).cwiseAbs().maxCoeff(), 1e-9);
  System independent = s;
  independent.C.pop_back();
  independent.c.conservativeResize(3);
  EXPECT_LE((x - kkt_solution(independent)).cwiseAbs().maxCoeff(), 1e-9);
}

// Projecting with zero values keeps a displacement within the constraints, and projecting twice
// changes nothing more.
TEST(LinearConstraints, AProjectedDisplacementStaysWithinAndProjectionIsIdempotent) {
  const System s = random_system(25, 3, 4, 11);
  const Eigen::LDLT<MatrixXd> K(s.K);
  const LinearConstraints cons(s.C, [&](const MatrixXd& rhs) { return K.solve(rhs).eval(); });
  MatrixXd dx = K.solve(s.b);
  cons.project(dx, VectorXd::Zero(cons.size()));
  EXPECT_LE(cons.values(dx).cwiseAbs().maxCoeff(), 1e-11);
  const MatrixXd once = dx;
  cons.project(dx, VectorXd::Zero(cons.size()));
  EXPECT_LE((dx - once).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(LinearConstraints, MismatchedShapesAreRefused) {
  const System s = random_system(10, 3, 2, 5);
  const Eigen::LDLT<MatrixXd> K(s.K);
  auto solve = [&](const MatrixXd& rhs) { return K.solve(rhs).eval(); };
  EXPECT_THROW(LinearConstraints({MatrixXd::Zero(10, 3), MatrixXd::Zero(9, 3)}, solve), std::invalid_argument);
  const LinearConstraints cons(s.C, solve);
  MatrixXd x = MatrixXd::Zero(10, 3);
  EXPECT_THROW(cons.project(x, VectorXd::Zero(3)), std::invalid_argument);
  MatrixXd wrong = MatrixXd::Zero(10, 2);
  EXPECT_THROW(cons.values(wrong), std::invalid_argument);
  const LinearConstraints none({}, solve);
  cons.project(x, s.c);  // no throw on a right-sized call
  none.project(x, VectorXd());
  EXPECT_EQ(none.size(), 0);
}
