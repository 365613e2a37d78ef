#include "support/arap_reference.h"

#include "core/solver/arap.h"

namespace slim::test {

Points arap_energy_gradient(const TetMesh& rest, const Points& V, const std::vector<Eigen::Matrix3d>& L,
                            const Eigen::VectorXd& anchors) {
  Points g = Points::Zero(V.rows(), 3);
  for (int t = 0; t < rest.T.rows(); ++t) {
    const double w = tet_volume(rest.V, rest.T.row(t));
    const Eigen::Matrix3d D = edge_matrix(V, rest.T.row(t)) - L[static_cast<size_t>(t)] * edge_matrix(rest.V, rest.T.row(t));
    for (int j = 0; j < 3; ++j) {
      g.row(rest.T(t, j + 1)) += 2.0 * w * D.col(j).transpose();
      g.row(rest.T(t, 0)) -= 2.0 * w * D.col(j).transpose();
    }
  }
  if (anchors.size()) g += 2.0 * (anchors.asDiagonal() * (V - rest.V)).eval();
  return g;
}

}  // namespace slim::test
