#include "core/volume_keeping.h"

#include <Eigen/Geometry>
#include <cmath>

namespace slim {

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
  // The surface moves linearly with lambda (the embedding is linear), and so does its centroid,
  // so Vol(lambda) = (d0 + d1 lambda + d2 lambda^2 + d3 lambda^3) / 6 exactly: one pass over the
  // faces for the coefficients, then Newton's method on the cubic alone.
  Points S, Su;
  embedded_positions(e, proposed, S);
  embedded_positions(e, u, Su);
  const Eigen::RowVector3d centre = S.colwise().mean(), centre_u = Su.colwise().mean();
  Eigen::Vector4d d = Eigen::Vector4d::Zero();
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Matrix3d P, Q;  // columns: the corners about the centroid, and their motion per unit lambda
    for (int k = 0; k < 3; ++k) {
      P.col(k) = (S.row(F(f, k)) - centre).transpose();
      Q.col(k) = (Su.row(F(f, k)) - centre_u).transpose();
    }
    const Eigen::Vector3d a = P.col(0), b = P.col(1), c = P.col(2), p = Q.col(0), q = Q.col(1), r = Q.col(2);
    d(0) += a.dot(b.cross(c));
    d(1) += p.dot(b.cross(c)) + a.dot(q.cross(c)) + a.dot(b.cross(r));
    d(2) += a.dot(q.cross(r)) + p.dot(b.cross(r)) + p.dot(q.cross(c));
    d(3) += p.dot(q.cross(r));
  }
  d /= 6.0;
  auto volume = [&](double l) { return d(0) + l * (d(1) + l * (d(2) + l * d(3))); };
  auto slope = [&](double l) { return d(1) + l * (2.0 * d(2) + l * 3.0 * d(3)); };
  double lambda = 0.0;
  for (int step = 0; step < 20 && std::abs(volume(lambda) - target) > 1e-12 * std::abs(target); ++step) {
    const double s = slope(lambda);
    if (!(std::abs(s) > 0.0) || !std::isfinite(s)) break;
    const double next = lambda + (target - volume(lambda)) / s;
    if (!std::isfinite(next)) break;
    lambda = next;
  }
  if (lambda != 0.0) proposed += lambda * u;
  return lambda;
}

}  // namespace slim
