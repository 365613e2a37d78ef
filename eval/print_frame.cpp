#include "print_frame.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/print/overhang.h"

namespace slim::eval {

int prusa_support_threshold(double alpha_max_deg) {
  if (!(alpha_max_deg >= 0.0 && alpha_max_deg < 90.0))
    throw std::invalid_argument("the self-supporting angle must be in [0, 90) degrees, got " +
                                std::to_string(alpha_max_deg));
  const int threshold = static_cast<int>(std::lround(90.0 - alpha_max_deg));
  if (threshold < 1)  // 0 would switch the slicer to its automatic threshold
    throw std::invalid_argument("a self-supporting angle of " + std::to_string(alpha_max_deg) +
                                " degrees rounds to a slicer threshold of 0, which PrusaSlicer reads as automatic");
  return threshold;
}

PrintFrame to_print_frame(const Surface& s, const Eigen::Vector3d& print_direction, double longest_side) {
  check_surface(s);
  if (s.V.rows() == 0) throw std::invalid_argument("the mesh has no vertices");
  const Eigen::Vector3d d = unit_print_direction(print_direction);
  PrintFrame out;
  if (d.z() < -1.0 + 1e-12) out.rotation = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  else out.rotation = Eigen::Quaterniond::FromTwoVectors(d, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  Points V = s.V * out.rotation.transpose();
  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const double longest = (hi - lo).maxCoeff();
  if (!(longest > 0.0)) throw std::invalid_argument("the mesh has no extent (all vertices coincide)");
  out.scale = longest_side > 0.0 ? longest_side / longest : 1.0;
  const Eigen::RowVector3d anchor(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z());
  V = (V.rowwise() - anchor) * out.scale;
  out.size = (hi - lo).transpose() * out.scale;
  out.surface.V = V;
  out.surface.F = s.F;
  return out;
}

}  // namespace slim::eval
