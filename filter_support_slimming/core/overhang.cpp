#include "core/overhang.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slim {

double self_supporting_tau(double alpha_max_deg) {
  if (!(alpha_max_deg >= 0.0 && alpha_max_deg < 90.0))
    throw std::invalid_argument("the self-supporting angle must be in [0, 90) degrees, got " +
                                std::to_string(alpha_max_deg));
  return std::sin(alpha_max_deg * M_PI / 180.0);
}

Eigen::Vector3d unit_print_direction(const Eigen::Vector3d& d) {
  const double len = d.norm();
  if (!std::isfinite(len) || len < 1e-12)
    throw std::invalid_argument("the print direction must be a non-zero vector");
  return d / len;
}

OverhangReport analyse_overhang(const Surface& s, const OverhangOptions& options) {
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to analyse");
  return analyse_overhang(CheckedSurface(s), options);
}

OverhangReport analyse_overhang(const CheckedSurface& checked, const OverhangOptions& options) {
  const Surface& s = checked.get();
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to analyse");
  const Eigen::Vector3d d = unit_print_direction(options.print_direction);
  const double tau = self_supporting_tau(options.alpha_max_deg);

  const Points n = face_normals(s);
  const Eigen::VectorXd area = face_areas(s);
  const Eigen::VectorXd height = s.V * d;  // every vertex's height along d

  OverhangReport r;
  r.plate_height = height.minCoeff();
  r.quality = n * d + Eigen::VectorXd::Constant(s.F.rows(), tau);
  r.risky.assign(static_cast<size_t>(s.F.rows()), false);
  r.on_plate.assign(static_cast<size_t>(s.F.rows()), false);
  r.total_area = area.sum();
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const auto fi = static_cast<size_t>(f);
    const double h0 = height(s.F(f, 0)), h1 = height(s.F(f, 1)), h2 = height(s.F(f, 2));
    const FaceSupport support = face_support(h0, h1, h2, r.plate_height, options.plate_tolerance, r.quality(f));
    if (support == FaceSupport::Plate) {
      r.on_plate[fi] = true;
      r.quality(f) = 1.0;  // carried by the plate: reads as safe on the colour ramp
      ++r.plate_count;
    } else if (support == FaceSupport::Risky) {
      r.risky[fi] = true;
      ++r.risky_count;
      r.risky_area += area(f);
      r.risky_deficit -= area(f) * r.quality(f);
      r.shadow_volume += face_shadow(area(f), n.row(f).dot(d), (h0 + h1 + h2) / 3.0 - r.plate_height);
    }
  }
  return r;
}

}  // namespace slim
