#include "core/print/overhang.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

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

  const Eigen::VectorXd height = s.V * d;  // every vertex's height along d

  OverhangReport r;
  r.plate_height = height.minCoeff();
  // Each face on the threads, in one pass (its normal, area, quality as face_normals, face_areas
  // and n · d + tau give them); then the sums in face order, as one pass makes them.
  const auto faces = static_cast<int>(s.F.rows());
  Eigen::VectorXd area(faces), shadow(faces);
  std::vector<FaceSupport> support(static_cast<size_t>(faces));
  r.quality.resize(faces);
#pragma omp parallel for schedule(static) if (faces > 65536)
  for (int f = 0; f < faces; ++f) {
    const Eigen::Vector3d cross = face_cross(s.V, s.F, f), n = unit_normal(cross);
    const double n_dot_d = n(0) * d(0) + n(1) * d(1) + n(2) * d(2);
    area(f) = 0.5 * cross.norm();
    r.quality(f) = n_dot_d + tau;
    const double h0 = height(s.F(f, 0)), h1 = height(s.F(f, 1)), h2 = height(s.F(f, 2));
    support[static_cast<size_t>(f)] = face_support(h0, h1, h2, r.plate_height, options.plate_tolerance, r.quality(f));
    if (support[static_cast<size_t>(f)] == FaceSupport::Risky)
      shadow(f) = face_shadow(area(f), n_dot_d, (h0 + h1 + h2) / 3.0 - r.plate_height);
  }
  r.risky.assign(static_cast<size_t>(faces), false);
  r.on_plate.assign(static_cast<size_t>(faces), false);
  r.total_area = area.sum();
  for (int f = 0; f < faces; ++f) {
    const auto fi = static_cast<size_t>(f);
    if (support[fi] == FaceSupport::Plate) {
      r.on_plate[fi] = true;
      r.quality(f) = 1.0;  // carried by the plate: reads as safe on the colour ramp
      ++r.plate_count;
    } else if (support[fi] == FaceSupport::Risky) {
      r.risky[fi] = true;
      ++r.risky_count;
      r.risky_area += area(f);
      r.risky_deficit -= area(f) * r.quality(f);
      r.shadow_volume += shadow(f);
    }
  }
  return r;
}

}  // namespace slim
