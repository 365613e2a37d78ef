// The part as the slicer sees it, and the slicer setting that matches our overhang rule.
#pragma once

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim::eval {

// PrusaSlicer's --support-material-threshold for a self-supporting angle alpha_max measured from
// the vertical (ours): the slicer measures the steepest printable slope from the horizontal, so it
// is 90 - alpha_max, in whole degrees (the slicer's option is an integer). Its 0 means
// "automatic", so an angle that would give 0 is refused. Throws std::invalid_argument unless
// 0 <= alpha_max_deg < 90 and 90 - alpha_max_deg rounds to 1..90.
int prusa_support_threshold(double alpha_max_deg);

struct PrintFrame {
  Surface surface;          // the part in the print frame: +Z up, resting on z = 0, centred in XY
  double scale = 1.0;       // uniform factor applied to the input
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // takes the print direction to +Z
  Eigen::Vector3d size = Eigen::Vector3d::Zero();          // bbox extent after the transform (mm)
};

// Turns the print direction onto +Z (the shortest rotation; a half turn about X for -Z), scales
// uniformly so the longest side of the bounding box is `longest_side` mm (<= 0 keeps the scale),
// and puts the lowest point on z = 0 with the bbox centred on the Z axis. Throws
// std::invalid_argument for a zero direction, a surface with no extent, or a bad surface.
PrintFrame to_print_frame(const Surface& s, const Eigen::Vector3d& print_direction, double longest_side);

}  // namespace slim::eval
