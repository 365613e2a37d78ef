// The part keeps its proportions: the six linear constraints on the domain's positions under
// which the best-fit affine map from the input's surface vertices to the result's has no
// stretch or squash to first order (proportions.h measures the same map).
//
//   std::vector<Points> C = stretch_constraints(input, embedding, domain_vertices);
//   arap.set_constraints(C, values(C, domain.V));   // held from then on by every global step
//
// The fit: X the input's #V by 3 vertices, Xc = X minus their centroid, Y the result's. Its linear
// part is I + B with B = (Xc^T Xc)^-1 Xc^T (Y - X), linear in Y, and Y = E V through the
// embedding's barycentric rows (embedding.h: E is #V by #DV, V the domain's #DV by 3 positions).
// The stretch is sym(B); its six entries (i <= j) are zero when
//   sum_v <C_ij.row(v), V.row(v)> = sum_v <C_ij.row(v), V0.row(v)>,  C_ij = column j of Z e_i^T
//   plus column i of Z e_j^T (one column for i = j),  Z = E^T Xc (Xc^T Xc)^-1  (#DV by 3),
// V0 the rest domain. A rotation of the whole part is antisymmetric in B and stays free (the plate
// holds it); a local reshaping that adds no global stretch is untouched.
// Inputs: input (#V by 3 mm, #F by 3), its embedding in a domain of domain_vertices vertices.
// Output: six #DV by 3 matrices (1/mm). A direction in which the input has no extent (below 1e-9
// of its largest) is left out of the fit, and its constraints are zero.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/domain/embedding.h"
#include "core/geometry/surface.h"

namespace slim {

std::vector<Points> stretch_constraints(const Surface& input, const Embedding& embedding, Eigen::Index domain_vertices);

// <C_k, V> for each k (the constraints' values at the positions V, #DV by 3).
Eigen::VectorXd constraint_values(const std::vector<Points>& C, const Points& V);

}  // namespace slim
