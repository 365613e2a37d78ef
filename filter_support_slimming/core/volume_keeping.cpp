#include "core/volume_keeping.h"

#include <Eigen/Geometry>
#include <cmath>

namespace slim {

namespace {

double volume_at(const Embedding& e, const Triangles& F, const Points& V, Points& surface) {
  embedded_positions(e, V, surface);
  return signed_volume(Surface{surface, F});
}

}  // namespace

Points embedded_volume_gradient(const Embedding& e, const Triangles& F, const Points& S, Eigen::Index domain_vertices) {
  // Vol = 1/6 sum over faces of a · (b x c) about the centroid; d/da = (b x c) / 6 summed over a's
  // faces, which for a closed surface is a third of the area-weighted normals around a.
  const Eigen::RowVector3d centre = S.colwise().mean();
  Points gS = Points::Zero(S.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = (S.row(F(f, 0)) - centre).transpose(), b = (S.row(F(f, 1)) - centre).transpose(),
                          c = (S.row(F(f, 2)) - centre).transpose();
    gS.row(F(f, 0)) += b.cross(c).transpose() / 6.0;
    gS.row(F(f, 1)) += c.cross(a).transpose() / 6.0;
    gS.row(F(f, 2)) += a.cross(b).transpose() / 6.0;
  }
  Points g = Points::Zero(domain_vertices, 3);
  for (Eigen::Index i = 0; i < S.rows(); ++i)
    for (int k = 0; k < 4; ++k) g.row(e.vertex_nodes(i, k)) += e.vertex_bary(i, k) * gS.row(i);
  return g;
}

Points volume_load(const Embedding& e, const Triangles& F, const Points& V_start) {
  Points surface;
  embedded_positions(e, V_start, surface);
  return embedded_volume_gradient(e, F, surface, V_start.rows());
}

double keep_volume(const Embedding& e, const Triangles& F, double target, const Points& u, Points& proposed) {
  Points surface;
  double volume = volume_at(e, F, proposed, surface);
  const Points base = proposed;
  double lambda = 0.0;
  for (int step = 0; step < 4 && std::abs(volume - target) > 1e-9 * std::abs(target); ++step) {
    const Points g = embedded_volume_gradient(e, F, surface, proposed.rows());
    const double slope = (g.array() * u.array()).sum();
    if (!(std::abs(slope) > 0.0) || !std::isfinite(slope)) break;
    lambda += (target - volume) / slope;
    proposed = base + lambda * u;
    volume = volume_at(e, F, proposed, surface);
  }
  return lambda;
}

}  // namespace slim
