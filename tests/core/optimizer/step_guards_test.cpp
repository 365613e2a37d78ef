// The step guards (core/optimizer/step_guards.h) one by one on a small tet grid: each is a pure function of
// (rest, current, proposed, tets), so each invariant is checked where it is made: the plate holds,
// the budget holds (a rigid group in one piece), the rolled-back and the cut-back shapes invert no
// tet.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/optimizer/step_guards.h"
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
  const std::vector<int> none(static_cast<size_t>(m.V.rows()), -1);
  const BudgetGuard outcome = keep_within_budget(m.V, m.V, proposed, budget, none);
  EXPECT_GT(outcome.projected, 0);
  EXPECT_EQ(outcome.groups_held, 0);
  int overshooting = 0;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    const Eigen::RowVector3d before = proposed_in.row(v) - m.V.row(v), after = proposed.row(v) - m.V.row(v);
    EXPECT_LE(after.norm(), budget * (1 + 1e-12)) << "vertex " << v;
    if (before.norm() > budget) {
      ++overshooting;
      EXPECT_NEAR(after.norm(), budget, 1e-12);                    // onto the ball
      EXPECT_NEAR(after.dot(before), after.norm() * before.norm(), 1e-12);  // the same direction
    } else {
      EXPECT_FALSE(moved(proposed, proposed_in, v));
    }
  }
  EXPECT_EQ(outcome.projected, overshooting);
  Points within = m.V;
  EXPECT_FALSE(keep_within_budget(m.V, m.V, within, budget, none).moved());
  EXPECT_EQ(within, m.V);
}

TEST(StepGuards, BudgetHoldsARigidGroupBackInOnePieceAndProjectsTheRest) {
  const TetMesh m = grid();
  const double budget = 0.25;
  const Points current = jittered(m.V, 0.05, 3);  // within the budget
  const Points proposed_in = jittered(m.V, 0.6, 4);
  // The group: the vertices of the top layer (z = 3), one rigid feature.
  std::vector<int> group(static_cast<size_t>(m.V.rows()), -1);
  std::vector<Eigen::Index> members;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (m.V(v, 2) == 3.0) group[static_cast<size_t>(v)] = 0, members.push_back(v);
  Points proposed = proposed_in;
  const BudgetGuard outcome = keep_within_budget(m.V, current, proposed, budget, group);
  EXPECT_EQ(outcome.groups_held, 1);
  EXPECT_GT(outcome.projected, 0);
  EXPECT_LE((proposed - m.V).rowwise().norm().maxCoeff(), budget * (1 + 1e-12));
  // The group: one fraction f for all its vertices, proposed = current + f (proposed_in - current),
  // the largest that fits (a little more overshoots).
  const Points step = proposed_in - current;
  const Eigen::Index first = members.front();
  const double f = (proposed.row(first) - current.row(first)).norm() / step.row(first).norm();
  EXPECT_GT(f, 0.0);
  EXPECT_LT(f, 1.0);
  double worst = 0.0;
  for (Eigen::Index v : members) {
    EXPECT_LT((proposed.row(v) - (current.row(v) + f * step.row(v))).cwiseAbs().maxCoeff(), 1e-12) << "vertex " << v;
    worst = std::max(worst, (current.row(v) + (f + 1e-6) * step.row(v) - m.V.row(v)).norm());
  }
  EXPECT_GT(worst, budget);
  // The others: projected on their own, exactly as without a group.
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    if (group[static_cast<size_t>(v)] >= 0) continue;
    const Eigen::RowVector3d before = proposed_in.row(v) - m.V.row(v);
    const Eigen::RowVector3d expected = before.norm() > budget ? Eigen::RowVector3d(m.V.row(v) + before * (budget / before.norm()))
                                                               : Eigen::RowVector3d(proposed_in.row(v));
    EXPECT_LT((proposed.row(v) - expected).cwiseAbs().maxCoeff(), 1e-12) << "vertex " << v;
  }
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
    if (listed) {
      EXPECT_TRUE(touches) << "tet " << t;  // only tets around the moved vertex
    }
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
  const std::vector<int> none(static_cast<size_t>(m.V.rows()), -1);
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

TEST(StepGuards, RollBackTakesARigidGroupBackWhole) {
  const TetMesh m = grid();
  const Points current = jittered(m.V, 0.05, 6);
  // A rigid group, the layer z = 1, moved as a body; one of its vertices pushed through the tets
  // around it as well.
  std::vector<int> group(static_cast<size_t>(m.V.rows()), -1);
  Points proposed = current;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (m.V(v, 2) == 1.0) group[static_cast<size_t>(v)] = 0, proposed.row(v) += Eigen::RowVector3d(0.05, 0.0, 0.0);
  const int inside = 2 + 5 * (2 + 5 * 1);
  proposed.row(inside) += Eigen::RowVector3d(0.0, 1.6, 0.0);
  proposed.row(0) += Eigen::RowVector3d(0.01, 0.0, 0.0);  // not in the group, not near
  const Points proposed_in = proposed;
  int held_back = 0;
  ASSERT_TRUE(roll_back_inverting(current, proposed, m.T, group, inverted_tets(proposed, m.T), held_back));
  EXPECT_TRUE(inverted_tets(proposed, m.T).empty());
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (group[static_cast<size_t>(v)] == 0) {
      EXPECT_EQ(proposed.row(v), current.row(v)) << "vertex " << v;
    }
  EXPECT_GE(held_back, 25);  // the whole layer
  EXPECT_EQ(proposed.row(0), proposed_in.row(0));
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
