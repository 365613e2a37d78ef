#include "core/optimizer/support_region.h"

#include <algorithm>
#include <limits>

#include "core/geometry/face_box_tree.h"
#include "core/platform/parallel_for.h"

namespace slim {

Eigen::VectorXd distance_to_faces(const Surface& input, const std::vector<bool>& faces, const Points& points) {
  Surface seeds;
  seeds.V = input.V;
  std::vector<int> kept;
  for (size_t f = 0; f < faces.size(); ++f)
    if (faces[f]) kept.push_back(static_cast<int>(f));
  Eigen::VectorXd dist = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  if (kept.empty()) return dist;
  seeds.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t k = 0; k < kept.size(); ++k) seeds.F.row(static_cast<Eigen::Index>(k)) = input.F.row(kept[k]);
  const FaceBoxTree tree(seeds);
  parallel_for(static_cast<int>(points.rows()), [&](int v) { dist(v) = tree.distance(points.row(v).transpose()); });
  return dist;
}

Eigen::VectorXd region_anchors(const Surface& input, const std::vector<bool>& risky, const TetMesh& domain,
                               double diagonal_mm, const RegionOptions& o) {
  if (!(o.stiffness > 0.0)) return Eigen::VectorXd();
  const Eigen::Index nv = domain.V.rows();
  Eigen::VectorXd volume = Eigen::VectorXd::Zero(nv);
  for (Eigen::Index t = 0; t < domain.T.rows(); ++t) {
    const double quarter = tet_volume(domain.V, domain.T.row(t)) / 4.0;
    for (int j = 0; j < 4; ++j) volume(domain.T(t, j)) += quarter;
  }
  const Eigen::VectorXd dist = distance_to_faces(input, risky, domain.V);
  const double free_mm = o.free_radius_share * diagonal_mm, ramp_mm = o.ramp_share * diagonal_mm;
  Eigen::VectorXd a(nv);
  for (Eigen::Index v = 0; v < nv; ++v) {
    double s = ramp_mm > 0.0 ? (dist(v) - free_mm) / ramp_mm : (dist(v) > free_mm ? 1.0 : 0.0);
    s = std::clamp(s, 0.0, 1.0);
    a(v) = o.stiffness * volume(v) * s * s * (3.0 - 2.0 * s);
  }
  return a;
}

}  // namespace slim
