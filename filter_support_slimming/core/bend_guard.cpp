#include "core/bend_guard.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace slim {

namespace {

int third_vertex(const Triangles& F, int f, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (F(f, k) != a && F(f, k) != b) return F(f, k);
  return F(f, 0);
}

Eigen::Vector3d face_normal(const Points& S, const Triangles& F, int f) {
  const Eigen::Vector3d a = S.row(F(f, 0)).transpose();
  return (S.row(F(f, 1)).transpose() - a).cross(S.row(F(f, 2)).transpose() - a);
}

}  // namespace

BendGuard::BendGuard(const Surface& input, const Embedding& embedding, double max_bend_deg)
    : input_(input), embedding_(embedding), max_bend_deg_(max_bend_deg), edges_(dihedral_edges(input)) {
  opposite_.reserve(edges_.size());
  for (const DihedralEdge& e : edges_)
    opposite_.push_back({third_vertex(input.F, e.f0, e.v0, e.v1), third_vertex(input.F, e.f1, e.v0, e.v1)});
}

std::vector<size_t> BendGuard::bent_edges(const Points& S) const {
  std::vector<size_t> bent;
  for (size_t i = 0; i < edges_.size(); ++i) {
    const DihedralEdge& e = edges_[i];
    const Eigen::Vector3d n0 = face_normal(S, input_.F, e.f0), n1 = face_normal(S, input_.F, e.f1);
    const Eigen::Vector3d dir = (S.row(e.v1) - S.row(e.v0)).transpose();
    const double angle = std::atan2(n0.cross(n1).dot(dir.normalized()), n0.dot(n1)) * 180.0 / M_PI;
    double change = std::abs(angle - e.angle_deg);
    if (change > 180.0) change = 360.0 - change;
    if (change > max_bend_deg_) bent.push_back(i);
  }
  return bent;
}

std::vector<int> BendGuard::faulty_tets(const Points& P) const {
  Points S;
  embedded_positions(embedding_, P, S);
  std::vector<int> tets;
  for (size_t i : bent_edges(S))
    for (int v : {edges_[i].v0, edges_[i].v1, opposite_[i][0], opposite_[i][1]}) tets.push_back(embedding_.vertex_tet(v));
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  return tets;
}

}  // namespace slim
