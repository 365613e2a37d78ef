#include "core/optimizer/surface_guards.h"

#include <algorithm>

namespace slim {

namespace {

void fold_tets(const Surface& input, const Embedding& embedding, const Points& S, std::vector<int>& tets) {
  for (Eigen::Index f = 0; f < input.F.rows(); ++f) {
    const Eigen::Vector3d a = face_cross(input.V, input.F, f), b = face_cross(S, input.F, f);
    if (!(a.squaredNorm() > 0.0 && b.squaredNorm() > 0.0 && a.dot(b) < 0.0)) continue;
    for (int k = 0; k < 3; ++k) tets.push_back(embedding.vertex_tet(input.F(f, k)));
  }
}

void sort_unique(std::vector<int>& tets) {
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
}

}  // namespace

std::vector<int> folding_tets(const Surface& input, const Embedding& embedding, const Points& P) {
  Points S(input.V.rows(), 3);
  embedded_positions(embedding, P, S);
  std::vector<int> tets;
  fold_tets(input, embedding, S, tets);
  sort_unique(tets);
  return tets;
}

SurfaceGuards::SurfaceGuards(const Surface& input, const Embedding& embedding, const Eigen::Vector3d& d,
                             std::optional<double> max_rise_pct)
    : input_(input), embedding_(embedding), d_(d) {
  if (!max_rise_pct || input.V.rows() == 0) return;
  const Eigen::VectorXd h = input.V * d;
  ceiling_ = h.maxCoeff() + *max_rise_pct / 100.0 * (h.maxCoeff() - h.minCoeff());
}

std::vector<int> SurfaceGuards::faulty_tets(const Points& P) const {
  Points S(input_.V.rows(), 3);
  embedded_positions(embedding_, P, S);
  std::vector<int> tets;
  fold_tets(input_, embedding_, S, tets);
  if (ceiling_)
    for (Eigen::Index v = 0; v < S.rows(); ++v)
      if (S.row(v).dot(d_) > *ceiling_) tets.push_back(embedding_.vertex_tet(v));
  sort_unique(tets);
  return tets;
}

}  // namespace slim
