// The step guards (core/step_guards.h) one by one on a small tet grid: each is a pure function of
// (rest, current, proposed, tets), so each invariant is checked where it is made: the plate holds,
// the budget holds, the rolled-back and the cut-back shapes invert no tet.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/step_guards.h"
#include "support/tet_grid.h"

using namespace slim;

namespace {

// A 4 x 4 x 3 grid of unit cubes on z = 0.
TetMesh grid() { return test::tet_grid(4, 4, 3); }

// Every vertex moved by a random offset of at most `reach`.
Points jittered(const Points& V, double reach, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-reach, reach);
  Points P = V;
  for (Eigen::Index v = 0; v < P.rows(); ++v) P.row(v) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  return P;
}

bool moved(const Points& a, const Points& b, Eigen::Index v) { return (a.row(v) - b.row(v)).norm() > 0.0; }

}  // namespace

TEST(StepGuards, PlateGuardLiftsExactlyTheVerticesBelowThePlate) {
  const TetMesh m = grid();
  const Eigen::Vector3d d = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const double plate = (m.V * d).minCoeff();
  const Points proposed_in = jittered(m.V, 0.4, 1);
  Points proposed = proposed_in;
  ASSERT_LT((proposed * d).minCoeff(), plate - 0.01);  // the jitter pushed some vertices under
  EXPECT_TRUE(keep_above_plate(proposed, d, plate));
  int lifted = 0;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    EXPECT_GE(proposed.row(v).dot(d), plate - 1e-12) << "vertex " << v;
    const bool was_below = proposed_in.row(v).dot(d) < plate;
    if (was_below) {
      ++lifted;
      EXPECT_NEAR(proposed.row(v).dot(d), plate, 1e-12);
      // Straight up: the move is along d.
      const Eigen::Vector3d move = (proposed.row(v) - proposed_in.row(v)).transpose();
      EXPECT_LT(move.cross(d).norm(), 1e-12);
    } else {
      EXPECT_FALSE(moved(proposed, proposed_in, v)) << "vertex " << v << " was above the plate";
    }
  }
  EXPECT_GT(lifted, 0);
  // Nothing is left below but rounding: a second pass moves nothing by more than that.
  Points again = proposed;
  keep_above_plate(again, d, plate);
  EXPECT_LT((again - proposed).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(StepGuards, PlateGuardHoldsAVertexExactlyOnThePlate) {
  const TetMesh m = grid();
  Points proposed = m.V;  // the bottom layer lies on z = 0 exactly
  EXPECT_FALSE(keep_above_plate(proposed, Eigen::Vector3d::UnitZ(), 0.0));
  EXPECT_EQ(proposed, m.V);
}

TEST(StepGuards, BudgetProjectsOnlyTheVerticesThatOvershoot) {
  const TetMesh m = grid();
  const double budget = 0.25;
  const Points proposed_in = jittered(m.V, 0.3, 2);
  Points proposed = proposed_in;
  const std::vector<bool> none(static_cast<size_t>(m.V.rows()), false);
  EXPECT_EQ(keep_within_budget(m.V, m.V, proposed, budget, none), BudgetGuard::Projected);
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    const Eigen::RowVector3d before = proposed_in.row(v) - m.V.row(v), after = proposed.row(v) - m.V.row(v);
    EXPECT_LE(after.norm(), budget * (1 + 1e-12)) << "vertex " << v;
    if (before.norm() > budget) {
      EXPECT_NEAR(after.norm(), budget, 1e-12);                    // onto the ball
      EXPECT_NEAR(after.dot(before), after.norm() * before.norm(), 1e-12);  // the same direction
    } else {
      EXPECT_FALSE(moved(proposed, proposed_in, v));
    }
  }
  Points within = m.V;
  EXPECT_EQ(keep_within_budget(m.V, m.V, within, budget, none), BudgetGuard::Within);
  EXPECT_EQ(within, m.V);
}

TEST(StepGuards, BudgetCutsTheWholeStepBackWhenARigidVertexWouldOvershoot) {
  const TetMesh m = grid();
  const double budget = 0.25;
  const Points current = jittered(m.V, 0.05, 3);  // within the budget
  const Points proposed_in = jittered(m.V, 0.6, 4);
  std::vector<bool> rigid(static_cast<size_t>(m.V.rows()), false);
  Eigen::Index far = 0;
  ((proposed_in - m.V).rowwise().norm()).maxCoeff(&far);
  rigid[static_cast<size_t>(far)] = true;
  Points proposed = proposed_in;
  EXPECT_EQ(keep_within_budget(m.V, current, proposed, budget, rigid), BudgetGuard::CutBack);
  // One fraction f for every vertex: proposed = current + f (proposed_in - current).
  const Points step = proposed_in - current;
  const double f = (proposed.row(far) - current.row(far)).norm() / step.row(far).norm();
  EXPECT_GT(f, 0.0);
  EXPECT_LT(f, 1.0);
  EXPECT_LT((proposed - (current + f * step)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((proposed - m.V).rowwise().norm().maxCoeff(), budget);
  // The largest such fraction: a little more overshoots.
  EXPECT_GT((current + (f + 1e-6) * step - m.V).rowwise().norm().maxCoeff(), budget);
}

TEST(StepGuards, InvertedTetsAreFoundExactly) {
  const TetMesh m = grid();
  EXPECT_TRUE(inverted_tets(m.V, m.T).empty());
  Points P = m.V;
  const int inside = 1 + 5 * (1 + 5 * 1);  // grid vertex (1, 1, 1)
  P.row(inside) += Eigen::RowVector3d(1.5, 0.0, 0.0);  // through its neighbours
  const std::vector<int> bad = inverted_tets(P, m.T);
  ASSERT_FALSE(bad.empty());
  EXPECT_TRUE(std::is_sorted(bad.begin(), bad.end()));
  for (int t = 0; t < m.T.rows(); ++t) {
    const bool listed = std::binary_search(bad.begin(), bad.end(), t);
    const bool touches = (m.T.row(t).array() == inside).any();
    if (listed) EXPECT_TRUE(touches) << "tet " << t;  // only tets around the moved vertex
  }
}

TEST(StepGuards, RollBackLeavesNoInvertedTetAndMovesOnlyWhatItMust) {
  const TetMesh m = grid();
  const Points current = jittered(m.V, 0.05, 5);
  Points proposed_in = current;
  const int inside = 2 + 5 * (2 + 5 * 1);  // grid vertex (2, 2, 1)
  proposed_in.row(inside) += Eigen::RowVector3d(0.0, 1.6, 0.0);
  proposed_in.row(0) += Eigen::RowVector3d(0.01, 0.02, 0.0);  // a harmless move far away
  Points proposed = proposed_in;
  const std::vector<bool> none(static_cast<size_t>(m.V.rows()), false);
  int held_back = 0;
  ASSERT_TRUE(roll_back_inverting(current, proposed, m.T, none, inverted_tets(proposed_in, m.T), held_back));
  EXPECT_TRUE(inverted_tets(proposed, m.T).empty());
  EXPECT_GT(held_back, 0);
  // Only vertices of the tets that inverted go back (held_back counts them, moved or not), and
  // exactly to where they were.
  int changed = 0;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    if (!moved(proposed, proposed_in, v)) continue;
    EXPECT_EQ(proposed.row(v), current.row(v)) << "a vertex that changed went back exactly";
    ++changed;
  }
  EXPECT_GE(changed, 1);
  EXPECT_LE(changed, held_back);
  EXPECT_LE(held_back, 4 * static_cast<int>(inverted_tets(proposed_in, m.T).size()) + 64);
  EXPECT_EQ(proposed.row(inside), current.row(inside));
  EXPECT_EQ(proposed.row(0), proposed_in.row(0));  // the harmless move stands
}

TEST(StepGuards, RollBackRefusesToMoveARigidVertexAlone) {
  const TetMesh m = grid();
  Points proposed = m.V;
  const int inside = 2 + 5 * (2 + 5 * 1);
  proposed.row(inside) += Eigen::RowVector3d(0.0, 1.6, 0.0);
  const Points proposed_in = proposed;
  std::vector<bool> rigid(static_cast<size_t>(m.V.rows()), false);
  rigid[static_cast<size_t>(inside)] = true;
  int held_back = 0;
  EXPECT_FALSE(roll_back_inverting(m.V, proposed, m.T, rigid, inverted_tets(proposed, m.T), held_back));
  EXPECT_EQ(proposed, proposed_in);  // untouched when it refuses
}

TEST(StepGuards, CutBackKeepsEveryTetPositiveAndGoesAsFarAsItCan) {
  const TetMesh m = grid();
  const Points current = m.V;
  Points proposed_in = current;
  const int inside = 1 + 5 * (2 + 5 * 1);
  proposed_in.row(inside) += Eigen::RowVector3d(2.0, 0.0, 0.3);
  Points proposed = proposed_in;
  cut_back_to_valid(current, proposed, m.T, inverted_tets(proposed_in, m.T));
  EXPECT_TRUE(inverted_tets(proposed, m.T).empty());
  const Points step = proposed_in - current;
  const double f = (proposed.row(inside) - current.row(inside)).norm() / step.row(inside).norm();
  EXPECT_GT(f, 0.1);
  EXPECT_LT(f, 1.0);
  EXPECT_LT((proposed - (current + f * step)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_FALSE(inverted_tets(current + (f + 1e-5) * step, m.T).empty());  // a little further inverts
}
