#include "core/print/overhang.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace slim {

OverhangReport analyse_overhang(const Surface& s, const PrintSetup& print) {
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to analyse");
  const CheckedSurface checked(s);
  return analyse_overhang(checked, print_rule(print, bbox_diagonal(s.V)));
}

OverhangReport analyse_overhang(const CheckedSurface& checked, const PrintRule& rule) {
  const Surface& s = checked.get();
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to analyse");
  const Eigen::Vector3d& d = rule.d;
  const double tau = rule.tau;

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
    support[static_cast<size_t>(f)] = face_support(h0, h1, h2, r.plate_height, rule.plate_tolerance_mm, r.quality(f));
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
