// The colour of how far a vertex moved, on VCG's (and so MeshLab's) ramp: blue for an unmoved
// vertex, through green and yellow, to red at `top_mm` (the deviation budget) and beyond. For the
// Support Slimming layer and the files the CLI writes, so both show the same colour.
//
//   Eigen::Matrix<unsigned char, 1, 4> rgba = displacement_ramp_colour(displacement_mm, top_mm);
//
// In: the displacement (mm, >= 0) and the ramp's top (mm; <= 0 is taken as 1 mm, so that a run
// that moved nothing is all blue). Out: RGBA, alpha 255.
#pragma once

#include <Eigen/Core>

#include <vcg/space/color4.h>

namespace slim::vcg_adapters {

inline Eigen::Matrix<unsigned char, 1, 4> displacement_ramp_colour(double displacement_mm, double top_mm) {
  // VCG's ramp runs red -> blue from its first bound to its second: from the top down to 0.
  const float top = top_mm > 0.0 ? float(top_mm) : 1.0f;
  const vcg::Color4b c = vcg::Color4b::ColorRamp(top, 0.0f, float(displacement_mm));
  return {c[0], c[1], c[2], c[3]};
}

}  // namespace slim::vcg_adapters
