#include "core/domain/voxel_grid.h"

#include <cmath>

#include <Eigen/Geometry>

namespace slim {

Eigen::Matrix3d print_frame(const Eigen::Vector3d& d) {
  int least = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(d(a)) < std::abs(d(least))) least = a;
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(least);
  const Eigen::Vector3d e1 = (axis - axis.dot(d) * d).normalized();
  const Eigen::Vector3d e2 = d.cross(e1);
  Eigen::Matrix3d frame;
  frame.row(0) = e1.transpose();
  frame.row(1) = e2.transpose();
  frame.row(2) = d.transpose();
  return frame;
}

}  // namespace slim
