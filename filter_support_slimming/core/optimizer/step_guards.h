// The guards a global step's solution passes before it is accepted. Each is a pure function of
// the rest shape (the domain at the start), the current shape (the last accepted iterate), the
// proposed shape (the global step's solution, as far as the guards before have left it) and the
// tets; all positions are #DV by 3 (mm), tets #DT by 4.
//
//   keep_above_plate(proposed, d, plate)
//     Every vertex below the plate (height along the unit print direction d under `plate`, mm)
//     moves straight up onto it. Returns whether any moved.
//   keep_within_budget(rest, current, proposed, budget, group)
//     The deviation budget, a constraint rather than a stop: the part of the step that would take a
//     vertex further than `budget` (mm) from its rest position is rolled back, by projecting its
//     displacement onto the budget ball. Surface vertices are convex combinations of domain
//     vertices, so none of them can overshoot either. A vertex with group[v] >= 0 (#DV: the rigid
//     feature it belongs to, -1 for none) is never moved alone, since that would bend the feature:
//     when one of a group's vertices would overshoot, the group's whole step is cut back to the
//     largest fraction f that fits (bisection; every vertex of the group goes to
//     current + f (proposed - current)), so the feature moves as one body and holds at its budget
//     while the rest of the part goes on. Returns how many vertices were projected and how many
//     groups were held back.
//   inverted_tets(P, T)
//     The tets of T with a non-positive volume in P, ascending.
//   roll_back_inverting(current, proposed, T, group, inverting, held_back)
//     The local inversion guard: the vertices of the `inverting` tets go back to where they were in
//     `current`, then those of the tets that this in turn inverts, until none does (all of them
//     back is `current` itself, valid), at most 64 rounds. A vertex of a group never goes back
//     alone: its whole group does (the feature stays where it was, in one piece). False, and
//     `proposed` untouched, when the rounds run out; else true, with the number of vertices held
//     back.
//   cut_back_to_valid(current, proposed, T, probe)
//     The paper's guard: `proposed` becomes current + f (proposed - current) for the largest f in
//     [0, 1] (bisection, 20 halvings) that keeps every tet positive. The bisection probes only the
//     tets that invert at the full step (a tet's volume is a cubic in f, so another could in
//     principle dip in between): the fraction found is checked on every tet, and should one be
//     inverted there, the bisection is redone over all of them.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/tet_mesh.h"

namespace slim {

bool keep_above_plate(Points& proposed, const Eigen::Vector3d& d, double plate);

struct BudgetGuard {
  int projected = 0;    // vertices projected onto the budget ball
  int groups_held = 0;  // groups whose step was cut back
  bool moved() const { return projected > 0 || groups_held > 0; }
};
BudgetGuard keep_within_budget(const Points& rest, const Points& current, Points& proposed, double budget,
                               const std::vector<int>& group);

std::vector<int> inverted_tets(const Points& P, const Tets& T);

bool roll_back_inverting(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& group,
                         std::vector<int> inverting, int& held_back);

// The same rolling back for any fault: `faulty(P)` lists the tets at fault in positions P
// (ascending). The rounds roll their vertices back until faulty() lists none.
bool roll_back_until(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& group,
                     std::vector<int> faulty_now, const std::function<std::vector<int>(const Points&)>& faulty,
                     int& held_back);

void cut_back_to_valid(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& probe);

}  // namespace slim
