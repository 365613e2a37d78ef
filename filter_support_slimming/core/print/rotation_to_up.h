// The rotation that turns a print direction onto +Z: the print pose's frame, for the support
// model (which sweeps the part with +Z up) and the orientation search (which turns the part into
// the pose it chose).
//
//   Eigen::Matrix3d r = rotation_to_up(d);   // r * d = +Z
//
// In: d, the print direction (any non-zero finite vector; it is normalised). Out: the rotation
// by the smallest angle, about d x Z; for d = -Z, the half-turn about X. Throws
// std::invalid_argument for a zero or non-finite d (unit_print_direction, print_setup.h).
#pragma once

#include <Eigen/Core>

namespace slim {

Eigen::Matrix3d rotation_to_up(const Eigen::Vector3d& d);

}  // namespace slim
