// The colour of a face quality n·d + sin(alpha_max) (overhang.h) on a fixed ramp, VCG's (and so
// MeshLab's) red-yellow-green-blue ramp, for the filters' layers and the files the CLI writes.
//
//   Eigen::Matrix<unsigned char, 1, 4> rgba = quality_ramp_colour(quality);
//
// The range is fixed, not fitted to each mesh: n·d + tau lies in [tau - 1, tau + 1] within
// [-1, 2], and a fixed [-1, 1] ramp gives the same colour to the same value on every mesh, with
// the risky/safe boundary (0) in the middle: red..yellow risky, green..blue safe.
#pragma once

#include <Eigen/Core>

#include <vcg/space/color4.h>

namespace slim::vcg_adapters {

constexpr double kQualityRampMin = -1.0;
constexpr double kQualityRampMax = 1.0;

inline Eigen::Matrix<unsigned char, 1, 4> quality_ramp_colour(double quality) {
  vcg::Color4b c;
  c.SetColorRamp(float(kQualityRampMin), float(kQualityRampMax), float(quality));
  return {c[0], c[1], c[2], c[3]};
}

}  // namespace slim::vcg_adapters
