#include "core/print/rotation_to_up.h"

#include <cmath>

#include <Eigen/Geometry>

#include "core/print/print_setup.h"

namespace slim {

Eigen::Matrix3d rotation_to_up(const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = unit_print_direction(d);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d axis = u.cross(up);
  const double sin_angle = axis.norm(), cos_angle = u.dot(up);
  if (sin_angle < 1e-15) {
    return cos_angle > 0.0 ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  }
  return Eigen::AngleAxisd(std::atan2(sin_angle, cos_angle), axis / sin_angle).toRotationMatrix();
}

}  // namespace slim
