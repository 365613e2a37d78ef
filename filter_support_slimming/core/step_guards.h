// The guards a global step's solution passes before it is accepted. Each is a pure function of
// the rest shape (the domain at the start), the current shape (the last accepted iterate), the
// proposed shape (the global step's solution, as far as the guards before have left it) and the
// tets; all positions are #DV by 3 (mm), tets #DT by 4.
//
//   keep_above_plate(proposed, d, plate)
//     Every vertex below the plate (height along the unit print direction d under `plate`, mm)
//     moves straight up onto it. Returns whether any moved.
//   keep_within_budget(rest, current, proposed, budget, together)
//     The deviation budget, a constraint rather than a stop: the part of the step that would take a
//     vertex further than `budget` (mm) from its rest position is rolled back, by projecting its
//     displacement onto the budget ball. Surface vertices are convex combinations of domain
//     vertices, so none of them can overshoot either. A vertex marked in `together` (#DV: a rigid
//     feature's) is never moved alone, since that would bend the feature: when one would overshoot,
//     the whole step is cut back to the largest fraction that fits instead (positions are linear
//     in it; bisection). Returns what it did.
//   inverted_tets(P, T)
//     The tets of T with a non-positive volume in P, ascending.
//   roll_back_inverting(current, proposed, T, together, inverting, held_back)
//     The local inversion guard: the vertices of the `inverting` tets go back to where they were in
//     `current`, then those of the tets that this in turn inverts, until none does (all of them
//     back is `current` itself, valid), at most 64 rounds. False, and `proposed` untouched, when it
//     would move a vertex of `together` alone or the rounds run out; else true, with the number
//     of vertices held back.
//   cut_back_to_valid(current, proposed, T, probe)
//     The paper's guard: `proposed` becomes current + f (proposed - current) for the largest f in
//     [0, 1] (bisection, 20 halvings) that keeps every tet positive. The bisection probes only the
//     tets that invert at the full step (a tet's volume is a cubic in f, so another could in
//     principle dip in between): the fraction found is checked on every tet, and should one be
//     inverted there, the bisection is redone over all of them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/tet_mesh.h"

namespace slim {

bool keep_above_plate(Points& proposed, const Eigen::Vector3d& d, double plate);

enum class BudgetGuard { Within, Projected, CutBack };
BudgetGuard keep_within_budget(const Points& rest, const Points& current, Points& proposed, double budget,
                               const std::vector<bool>& together);

std::vector<int> inverted_tets(const Points& P, const Tets& T);

bool roll_back_inverting(const Points& current, Points& proposed, const Tets& T, const std::vector<bool>& together,
                         std::vector<int> inverting, int& held_back);

void cut_back_to_valid(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& probe);

}  // namespace slim
