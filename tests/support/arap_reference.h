// An independent gradient of the global step's energy (core/solver/arap.h), written out from its
// definition and not from the solver's assembly, for tests that check the solver's minimiser.
//
//   E(V) = sum_t w_t ||V_t - L_t V_t^0||^2 + sum_v a_v ||v - v^0||^2
//   with D = V_t - L_t V_t^0 (edge matrices): dE/dv_j = 2 w_t D_j (j = 1..3), dE/dv_0 = -2 w_t
//   (D_1 + D_2 + D_3), and 2 a_v (v - v^0) from the springs.
// Inputs: rest (#V by 3 mm, #T by 4), V (#V by 3), L (#T), w_t the rest volumes, anchors #V or
// empty. Output: #V by 3.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/tet_mesh.h"

namespace slim::test {

Points arap_energy_gradient(const TetMesh& rest, const Points& V, const std::vector<Eigen::Matrix3d>& L,
                            const Eigen::VectorXd& anchors = Eigen::VectorXd());

}  // namespace slim::test
